//! Pixel tests on generated meshes whose pictures are known by hand.

use envelope_mesh::TriangleSoup;
use envelope_mesh::generate::{box_mesh, icosphere};
use envelope_render::plot::{Series, faces_vs_epsilon_png, faces_vs_epsilon_svg};
use envelope_render::ramp::viridis;
use envelope_render::{
    Canvas, Panel, Projection, RenderError, Size, Style, View, render, render_strip,
};
use glam::DVec3;

const WHITE: [u8; 3] = [255, 255, 255];

fn front() -> Style {
    Style {
        view: View::new(0.0, 0.0).unwrap(),
        ..Style::default()
    }
}

fn picture(mesh: &TriangleSoup, style: &Style, scalars: Option<&[f64]>) -> Canvas {
    let panel = Panel {
        mesh,
        caption: "",
        scalars,
    };
    render(&panel, style, Size::new(100, 100).unwrap()).unwrap()
}

/// Sum of the three channels: lower is darker.
fn darkness(c: [u8; 3]) -> u32 {
    765 - c.iter().map(|&v| u32::from(v)).sum::<u32>()
}

#[test]
fn a_cube_from_the_front_fills_the_middle_and_leaves_the_corners() {
    let cube = box_mesh(DVec3::ONE, 1);
    let c = picture(&cube, &front(), None);
    let centre = c.pixel(50, 50).unwrap();
    assert_ne!(centre, WHITE);
    // The front face is square to the view: lit, not black.
    assert!(
        darkness(centre) > 30 && darkness(centre) < 400,
        "{centre:?}"
    );
    for (x, y) in [(0, 0), (99, 0), (0, 99), (99, 99)] {
        assert_eq!(c.pixel(x, y), Some(WHITE), "corner {x},{y}");
    }
    // Orthographic and fitted with a 5 % margin: the face covers 90 % of each side.
    assert_ne!(c.pixel(7, 50), Some(WHITE));
    assert_eq!(c.pixel(3, 50), Some(WHITE));
}

#[test]
fn perspective_keeps_the_mesh_in_frame() {
    let cube = box_mesh(DVec3::ONE, 2);
    let view = View::new(35.0, 30.0)
        .unwrap()
        .with_projection(Projection::Perspective { fov_degrees: 40.0 })
        .unwrap();
    let c = picture(
        &cube,
        &Style {
            view,
            ..Style::default()
        },
        None,
    );
    assert_ne!(c.pixel(50, 50), Some(WHITE));
    for x in 0..100 {
        for y in [0, 99] {
            assert_eq!(c.pixel(x, y), Some(WHITE), "edge pixel {x},{y}");
            assert_eq!(c.pixel(y, x), Some(WHITE), "edge pixel {y},{x}");
        }
    }
}

#[test]
fn the_same_input_gives_the_same_bytes() {
    let sphere = icosphere(2, 1.0);
    let values: Vec<f64> = sphere.positions.iter().map(|p| p.x).collect();
    let style = Style {
        wireframe: true,
        ..Style::default()
    };
    let panel = Panel {
        mesh: &sphere,
        caption: "sphere  320 faces",
        scalars: Some(&values),
    };
    let size = Size::new(120, 90).unwrap();
    let a = render(&panel, &style, size).unwrap().to_png().unwrap();
    let b = render(&panel, &style, size).unwrap().to_png().unwrap();
    assert_eq!(a, b);
}

#[test]
fn the_wireframe_darkens_edge_pixels_only() {
    let cube = box_mesh(DVec3::ONE, 1);
    let plain = picture(&cube, &front(), None);
    let wired = picture(
        &cube,
        &Style {
            wireframe: true,
            ..front()
        },
        None,
    );
    // The front face is two triangles: their diagonal crosses the centre.
    assert!(darkness(wired.pixel(50, 50).unwrap()) > darkness(plain.pixel(50, 50).unwrap()) + 20);
    // Away from every edge (a quarter of the way along the other diagonal), no change.
    assert_eq!(wired.pixel(30, 70), plain.pixel(30, 70));
    let mut changed = 0;
    for y in 0..100 {
        for x in 0..100 {
            let (p, w) = (plain.pixel(x, y).unwrap(), wired.pixel(x, y).unwrap());
            if p != w {
                changed += 1;
                assert!(darkness(w) > darkness(p), "{x},{y}: {p:?} -> {w:?}");
            }
        }
    }
    // Outline and diagonal: a few hundred pixels, not the whole face.
    assert!((200..2000).contains(&changed), "{changed}");
}

#[test]
fn back_faces_take_the_warm_tint() {
    let facing = TriangleSoup::from_raw(
        &[[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 1.0, 0.0]],
        &[[0, 1, 2]],
    );
    let away = TriangleSoup::from_raw(&facing_positions(&facing), &[[0, 2, 1]]);
    let f = picture(&facing, &front(), None).pixel(50, 60).unwrap();
    let b = picture(&away, &front(), None).pixel(50, 60).unwrap();
    assert!(f[2] > f[0], "front face bluish: {f:?}");
    assert!(b[0] > b[2], "back face warm: {b:?}");
}

fn facing_positions(s: &TriangleSoup) -> Vec<[f64; 3]> {
    s.positions.iter().map(|p| p.to_array()).collect()
}

#[test]
fn values_come_out_near_the_ends_of_the_ramp() {
    // A square facing the camera, the value rising from left (0) to right (1).
    let square = TriangleSoup::from_raw(
        &[
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
        ],
        &[[0, 1, 2], [0, 2, 3]],
    );
    let values = [0.0, 1.0, 1.0, 0.0];
    let c = picture(&square, &front(), Some(&values));
    let (low, high) = (viridis(0.0), viridis(1.0));
    let near = |p: [u8; 3], q: [u8; 3]| {
        p.iter()
            .zip(q)
            .map(|(&a, b)| (f64::from(a) - f64::from(b)).powi(2))
            .sum::<f64>()
    };
    // Row 40 crosses the square, then (after a white gap) the colour bar.
    let row: Vec<[u8; 3]> = (0..100).map(|x| c.pixel(x, 40).unwrap()).collect();
    let first = row.iter().position(|&p| p != WHITE).unwrap();
    let gap = first + row[first..].iter().position(|&p| p == WHITE).unwrap();
    let bar = gap + row[gap..].iter().position(|&p| p != WHITE).unwrap();
    // Lit almost head-on: the ramp's colours, a little darker.
    let (left, right) = (row[first + 1], row[gap - 2]);
    assert!(near(left, low) < near(left, high), "{left:?}");
    assert!(left[2] > left[1], "purple at the low end: {left:?}");
    assert!(near(right, high) < near(right, low), "{right:?}");
    assert!(
        right[0] > 150 && right[1] > 150 && right[2] < 80,
        "yellow: {right:?}"
    );
    // The colour bar is not shaded: the ramp's ends at its top and bottom.
    let (top, bottom) = (
        c.pixel(bar as u32 + 2, 6).unwrap(),
        c.pixel(bar as u32 + 2, 93).unwrap(),
    );
    assert!(near(top, high) < 100.0, "{top:?}");
    assert!(near(bottom, low) < 100.0, "{bottom:?}");
}

#[test]
fn bad_input_is_refused_with_its_reason() {
    let tri = TriangleSoup::from_raw(&[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], &[[0, 1, 3]]);
    let panel = Panel {
        mesh: &tri,
        caption: "",
        scalars: None,
    };
    let size = Size::new(32, 32).unwrap();
    assert_eq!(
        render(&panel, &Style::default(), size),
        Err(RenderError::Index {
            face: 0,
            vertex: 3,
            vertices: 3
        })
    );
    let ok = icosphere(0, 1.0);
    let short = [1.0];
    let panel = Panel {
        mesh: &ok,
        caption: "",
        scalars: Some(&short),
    };
    assert!(matches!(
        render(&panel, &Style::default(), size),
        Err(RenderError::Scalars { got: 1, .. })
    ));
    assert_eq!(
        render_strip(&[], &Style::default(), size),
        Err(RenderError::NoPanels)
    );
    let big = Size::new(8192, 8192).unwrap();
    let panel = Panel {
        mesh: &ok,
        caption: "",
        scalars: None,
    };
    assert!(matches!(
        render_strip(&[panel, panel], &Style::default(), big),
        Err(RenderError::TooLarge { .. })
    ));
}

#[test]
fn pngs_decode_to_the_requested_size() {
    let sphere = icosphere(1, 1.0);
    let panel = Panel {
        mesh: &sphere,
        caption: "sphere",
        scalars: None,
    };
    let png = render_strip(&[panel; 3], &Style::default(), Size::new(70, 50).unwrap())
        .unwrap()
        .to_png()
        .unwrap();
    let decoder = png::Decoder::new(std::io::Cursor::new(png));
    let reader = decoder.read_info().unwrap();
    let info = reader.info();
    assert_eq!((info.width, info.height), (210, 50));
    assert_eq!(info.color_type, png::ColorType::Rgb);

    let series = [Series {
        name: "cup".into(),
        points: vec![(0.1, 900.0), (1.0, 200.0)],
    }];
    let png = faces_vs_epsilon_png("t", &series, Size::new(300, 200).unwrap()).unwrap();
    let reader = png::Decoder::new(std::io::Cursor::new(png))
        .read_info()
        .unwrap();
    assert_eq!((reader.info().width, reader.info().height), (300, 200));
}

#[test]
fn the_svg_plot_is_well_formed_and_names_every_series() {
    let series = [
        Series {
            name: "cup & saucer".into(),
            points: vec![(1.0 / 64.0, 2000.0), (0.125, 600.0), (1.0, 150.0)],
        },
        Series {
            name: "bunny".into(),
            // Level 0 (epsilon 0) cannot be on a log axis: left out, not an error.
            points: vec![(0.0, 70_000.0), (0.125, 2600.0), (1.0, 350.0)],
        },
    ];
    let size = Size::new(640, 400).unwrap();
    let svg = faces_vs_epsilon_svg("faces against epsilon", &series, size).unwrap();
    let doc = roxmltree::Document::parse(&svg).expect("well-formed XML");
    let texts: Vec<String> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text().map(|t| t.trim().to_string()))
        .collect();
    for name in ["cup & saucer", "bunny", "faces against epsilon", "faces"] {
        assert!(texts.iter().any(|t| t == name), "{name} not in {texts:?}");
    }
    assert_eq!(
        svg,
        faces_vs_epsilon_svg("faces against epsilon", &series, size).unwrap()
    );
}

#[test]
fn one_camera_lines_panels_up_even_beside_a_colour_bar() {
    let sphere = icosphere(2, 1.0);
    let values: Vec<f64> = sphere.positions.iter().map(|p| p.y).collect();
    let plain = Panel {
        mesh: &sphere,
        caption: "",
        scalars: None,
    };
    let coloured = Panel {
        scalars: Some(&values),
        ..plain
    };
    let style = Style {
        same_scale: true,
        ..front()
    };
    let c = render_strip(&[plain, coloured], &style, Size::new(100, 80).unwrap()).unwrap();
    // The first covered pixel of the middle row, from each panel's left edge.
    let first = |left: u32| (0..100).find(|&x| c.pixel(left + x, 40) != Some(WHITE));
    assert_eq!(first(1), first(101));
    assert!(first(1).is_some());
}
