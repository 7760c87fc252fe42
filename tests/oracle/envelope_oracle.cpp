// envelope-oracle: exact cross-check oracle for the envelope project, backed by CGAL 5.5 and
// OpenMesh 9. Build with tests/oracle/build.sh; the Rust client is tests/src/oracle.rs.
//
// ============================================================================================
// PROTOCOL (version 1): line oriented, UTF-8/ASCII, '\n' line ends.
//
// Requests (stdin, or built from argv in one-shot mode). Blank lines and lines starting with
// '#' are ignored between requests. A request is a header line `CMD [ARGS...]` followed by a
// command-specific number of body lines. Numbers may be written as C99 hex floats (`%a`,
// e.g. `0x1.8p+1`, `-0x0p+0`: exact, preferred) or decimal (`%.17g`, also exact for doubles);
// they are parsed with strtod. Paths are NOT on the header line: each path is a body line of
// its own (the whole line is the path, so spaces are fine; newlines are not).
//
//   version                              (no body)
//   orient3d N      + N lines: ax ay az bx by bz cx cy cz dx dy dz
//   orient2d N      + N lines: ax ay bx by cx cy
//   tri_tri N       + N lines: 9 numbers of T1 then 9 numbers of T2
//   seg_tri N       + N lines: 6 numbers of segment (p q) then 9 numbers of triangle (a b c)
//   point_tri_sqdist N + N lines: px py pz ax ay az bx by bz cx cy cz eps2
//   self_intersections [--soup] [--time] + 1 line: PATH
//   hausdorff ERROR_BOUND                + 2 lines: PATH_A, PATH_B
//   hausdorff_approx POINTS_ON_FACES     + 2 lines: PATH_A, PATH_B
//   topology                             + 1 line: PATH
//
// Responses (stdout). Every response is a header line followed by exactly n payload lines:
//   ok CMD n [key=value ...]
//   err CMD message...                    (no payload; the request's body was consumed)
// Payloads:
//   orient3d / orient2d : n=N lines, each -1, 0 or 1. orient3d(a,b,c,d) is CGAL::orientation,
//       i.e. sign(((b-a) x (c-a)) . (d-a)) (unit tet 0,e1,e2,e3 -> 1; this is the OPPOSITE of
//       Shewchuk's/robust's orient3d). orient2d(a,b,c) = sign((b-a) x (c-a)) (CCW -> 1).
//   tri_tri / seg_tri   : n=N lines, each 0 or 1: do the CLOSED point sets intersect.
//       Degenerate inputs are classified exactly (collinear triangle -> segment between its two
//       extreme points; coincident points -> point) and the matching CGAL::do_intersect is used.
//   point_tri_sqdist    : n=N lines, each -1, 0 or 1 = sign(sqdist(p, T) - eps2), exact
//       (Epeck squared_distance; degenerate T handled as above; eps2 is taken as given).
//   self_intersections  : header `ok self_intersections K kind=mesh|soup vertices=V faces=F`
//       then K lines `i j` (i <= j, sorted), face indices in the FILE's face order. `i i` marks a
//       degenerate (collinear) face, as PMP::self_intersections reports it. Files must be
//       triangle-only (an `err` otherwise: no silent triangulation). kind=mesh: the soup is a
//       valid polygon mesh and PMP::self_intersections on a Surface_mesh was used; kind=soup:
//       not a valid mesh (non-manifold, ...), so a re-implementation of PMP's rule on the soup's
//       vertex indices is used (same box filter, same shared-edge/shared-vertex logic).
//       --soup forces the soup path even for valid meshes (for cross-checking the two).
//       --time: header `ok self_intersections_time 0 kind=.. intersects=0|1 seconds=S
//       load_seconds=L`: S times only does_self_intersect (soup: the full soup check).
//   hausdorff           : `ok hausdorff 0 distance=HEX decimal=DEC` one-sided A->B,
//       PMP::bounded_error_Hausdorff_distance<Sequential_tag>(A, B, bound). Both must be
//       triangle meshes (kind=mesh).
//   hausdorff_approx    : same format, PMP::approximate_Hausdorff_distance A->B with
//       number_of_points_on_faces(P) and random_seed(0) (a lower bound only).
//   topology            : n=2 payload lines, each `key=value` pairs:
//       `openmesh loaded=1 V= F= E= isolated= borders= components= chi= genus= file_polygons=`
//       `cgal loaded=1 kind=mesh V= F= E= isolated= borders= components= chi= genus=`
//       or `cgal loaded=0 kind=soup V= F=` (soup not a polygon mesh) / `... loaded=0 error=..`.
//       chi = V - E + F over non-isolated vertices. Components are face components (OpenMesh:
//       faces joined by shared vertices; CGAL: PMP::connected_components, edge-adjacent);
//       isolated vertices are counted apart. borders = number of boundary halfedge cycles.
//       genus = sum over components c of (2 - chi_c - b_c)/2, or -1 when some term is not a
//       nonnegative integer (non-orientable / non-manifold). OpenMesh's TriMesh triangulates
//       polygons (E, F then differ from CGAL's polygon counts; V, chi, genus do not) and drops
//       faces it cannot add (file_polygons - F tells how many, file_polygons from CGAL's reader).
//   version             : `ok version 0 protocol=1 cgal=X openmesh=Y`
//
// One-shot command line (for humans): envelope-oracle topology FILE
//   | self_intersections [--soup] [--time] FILE | hausdorff A B BOUND | hausdorff_approx A B N
//   | version. With no arguments (or `serve`) it serves the stdin protocol.
// Exit code: 0 unless stdin could not be read; per-request failures are `err` lines.
// ============================================================================================

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/version.h>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <numeric>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace PMP = CGAL::Polygon_mesh_processing;

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using P3 = K::Point_3;
using P2 = K::Point_2;
using Mesh = CGAL::Surface_mesh<P3>;
using face_descriptor = boost::graph_traits<Mesh>::face_descriptor;
using halfedge_descriptor = boost::graph_traits<Mesh>::halfedge_descriptor;
using OMesh = OpenMesh::TriMesh_ArrayKernelT<>;

namespace {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string hexf(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", x);
  return buf;
}
std::string decf(double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

// ------------------------------------------------------------------ input helpers
class Input {
 public:
  explicit Input(std::istream& in) : in_(in) {}
  bool next_line(std::string& line) {
    if (!std::getline(in_, line)) return false;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  }

 private:
  std::istream& in_;
};

std::vector<std::string> split_ws(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream is(s);
  std::string t;
  while (is >> t) out.push_back(t);
  return out;
}

double parse_num(const std::string& t) {
  const char* b = t.c_str();
  char* e = nullptr;
  double v = std::strtod(b, &e);
  if (e == b || *e != '\0') throw Error("bad number '" + t + "'");
  return v;
}

std::vector<double> parse_nums(const std::string& line, std::size_t expect) {
  std::vector<std::string> toks = split_ws(line);
  if (toks.size() != expect)
    throw Error("expected " + std::to_string(expect) + " numbers, got " +
                std::to_string(toks.size()));
  std::vector<double> v;
  v.reserve(expect);
  for (const auto& t : toks) v.push_back(parse_num(t));
  return v;
}

long parse_count(const std::string& t) {
  char* e = nullptr;
  long n = std::strtol(t.c_str(), &e, 10);
  if (e == t.c_str() || *e != '\0' || n < 0) throw Error("bad count '" + t + "'");
  return n;
}

// ------------------------------------------------------------------ simplices (exact classification)
template <class Kern>
struct Simplex {
  using Pt = typename Kern::Point_3;
  int dim = 2;  // 0 point, 1 segment, 2 triangle
  Pt p[3];
};

template <class Kern>
Simplex<Kern> make_simplex(const typename Kern::Point_3& a, const typename Kern::Point_3& b,
                           const typename Kern::Point_3& c) {
  Simplex<Kern> s;
  if (!CGAL::collinear(a, b, c)) {
    s.dim = 2;
    s.p[0] = a, s.p[1] = b, s.p[2] = c;
    return s;
  }
  if (a == b && b == c) {
    s.dim = 0;
    s.p[0] = a;
    return s;
  }
  // Collinear, not all equal: the extreme pair is the one the third point lies between.
  s.dim = 1;
  if (CGAL::collinear_are_ordered_along_line(a, c, b) && a != b) {
    s.p[0] = a, s.p[1] = b;
  } else if (CGAL::collinear_are_ordered_along_line(a, b, c) && a != c) {
    s.p[0] = a, s.p[1] = c;
  } else {
    s.p[0] = b, s.p[1] = c;
  }
  return s;
}

template <class Kern>
Simplex<Kern> make_simplex(const typename Kern::Point_3& a, const typename Kern::Point_3& b) {
  Simplex<Kern> s;
  if (a == b) {
    s.dim = 0;
    s.p[0] = a;
  } else {
    s.dim = 1;
    s.p[0] = a, s.p[1] = b;
  }
  return s;
}

bool simplices_intersect(const Simplex<K>& x, const Simplex<K>& y) {
  using S3 = K::Segment_3;
  using T3 = K::Triangle_3;
  if (x.dim < y.dim) return simplices_intersect(y, x);
  // now x.dim >= y.dim
  if (x.dim == 0) return x.p[0] == y.p[0];
  if (x.dim == 1) {
    S3 s(x.p[0], x.p[1]);
    if (y.dim == 0) return s.has_on(y.p[0]);
    return CGAL::do_intersect(s, S3(y.p[0], y.p[1]));
  }
  T3 t(x.p[0], x.p[1], x.p[2]);
  if (y.dim == 0) return CGAL::do_intersect(t, y.p[0]);
  if (y.dim == 1) return CGAL::do_intersect(t, S3(y.p[0], y.p[1]));
  return CGAL::do_intersect(t, T3(y.p[0], y.p[1], y.p[2]));
}

EK::FT sqdist_point_simplex(const EK::Point_3& q, const Simplex<EK>& s) {
  if (s.dim == 0) return CGAL::squared_distance(q, s.p[0]);
  if (s.dim == 1) return CGAL::squared_distance(q, EK::Segment_3(s.p[0], s.p[1]));
  return CGAL::squared_distance(q, EK::Triangle_3(s.p[0], s.p[1], s.p[2]));
}

// ------------------------------------------------------------------ mesh loading
struct Soup {
  std::vector<P3> pts;
  std::vector<std::vector<std::size_t>> polys;
};

Soup read_soup(const std::string& path) {
  Soup s;
  if (!CGAL::IO::read_polygon_soup(path, s.pts, s.polys, CGAL::parameters::verbose(false)))
    throw Error("cannot read polygon soup from '" + path + "'");
  for (const auto& poly : s.polys)
    for (std::size_t v : poly)
      if (v >= s.pts.size()) throw Error("vertex index out of range in '" + path + "'");
  return s;
}

void require_triangles(const Soup& s) {
  for (std::size_t i = 0; i < s.polys.size(); ++i)
    if (s.polys[i].size() != 3)
      throw Error("face " + std::to_string(i) + " has " + std::to_string(s.polys[i].size()) +
                  " vertices; only triangle meshes are accepted (triangulate first)");
}

// Builds a Surface_mesh keeping vertex and face order (checked). Returns false if the soup is
// not a valid polygon mesh.
bool soup_to_mesh(const Soup& s, Mesh& m) {
  if (!PMP::is_polygon_soup_a_polygon_mesh(s.polys)) return false;
  PMP::polygon_soup_to_polygon_mesh(s.pts, s.polys, m);
  if (m.number_of_vertices() != s.pts.size() || m.number_of_faces() != s.polys.size())
    throw Error("internal: Surface_mesh element counts differ from the soup");
  for (std::size_t i = 0; i < s.polys.size(); ++i) {
    face_descriptor f(static_cast<Mesh::size_type>(i));
    std::vector<std::size_t> vs;
    for (auto v : CGAL::vertices_around_face(m.halfedge(f), m)) vs.push_back(std::size_t(v));
    const auto& p = s.polys[i];
    bool same = false;
    if (vs.size() == p.size())
      for (std::size_t r = 0; r < p.size() && !same; ++r) {
        bool ok = true;
        for (std::size_t k = 0; k < p.size(); ++k) ok = ok && vs[(k + r) % p.size()] == p[k];
        same = ok;
      }
    if (!same) throw Error("internal: Surface_mesh face order differs from the file's");
  }
  return true;
}

Mesh load_triangle_mesh(const std::string& path) {
  Soup s = read_soup(path);
  require_triangles(s);
  if (s.polys.empty()) throw Error("'" + path + "' has no faces");
  Mesh m;
  if (!soup_to_mesh(s, m))
    throw Error("'" + path + "' is not a valid polygon mesh (polygon soup)");
  return m;
}

// ------------------------------------------------------------------ soup self-intersections
// Mirrors CGAL 5.5 PMP::internal::do_faces_intersect, with adjacency taken from the soup's
// vertex indices instead of halfedges.
bool soup_faces_intersect(const Soup& s, std::size_t fa, std::size_t fb) {
  const auto& a = s.polys[fa];
  const auto& b = s.polys[fb];
  const auto& P = s.pts;
  int shared = 0, ia = -1, ib = -1;
  int sa[3] = {0, 0, 0}, sb[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a[i] == b[j]) {
        ++shared;
        sa[i] = 1, sb[j] = 1;
        ia = i, ib = j;
      }
  if (shared >= 3) return true;  // same three vertices: coincident faces
  if (shared == 2) {
    int ra = 0, rb = 0;  // the non-shared vertex of each
    while (sa[ra]) ++ra;
    while (sb[rb]) ++rb;
    const P3& r = P[a[ra]];
    const P3& q0 = P[a[(ra + 1) % 3]];
    const P3& q1 = P[a[(ra + 2) % 3]];
    const P3& o = P[b[rb]];
    // PMP: coplanar(hv...) && coplanar_orientation(e0, e1, r, o) == POSITIVE, i.e. the opposite
    // vertices lie on the same side of the shared edge's line within their common plane.
    return CGAL::coplanar(q0, q1, r, o) && CGAL::coplanar_orientation(q0, q1, r, o) == CGAL::POSITIVE;
  }
  K::Triangle_3 ta(P[a[0]], P[a[1]], P[a[2]]);
  K::Triangle_3 tb(P[b[0]], P[b[1]], P[b[2]]);
  if (shared == 1) {
    K::Segment_3 s1(P[a[(ia + 1) % 3]], P[a[(ia + 2) % 3]]);
    K::Segment_3 s2(P[b[(ib + 1) % 3]], P[b[(ib + 2) % 3]]);
    return CGAL::do_intersect(ta, s2) || CGAL::do_intersect(tb, s1);
  }
  return CGAL::do_intersect(ta, tb);
}

std::vector<std::pair<std::size_t, std::size_t>> soup_self_intersections(const Soup& s) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t,
                                                       CGAL::Box_intersection_d::ID_FROM_BOX_ADDRESS>;
  std::vector<std::pair<std::size_t, std::size_t>> out;
  std::vector<Box> boxes;
  boxes.reserve(s.polys.size());
  for (std::size_t f = 0; f < s.polys.size(); ++f) {
    const auto& t = s.polys[f];
    const P3 &p = s.pts[t[0]], &q = s.pts[t[1]], &r = s.pts[t[2]];
    if (CGAL::collinear(p, q, r))
      out.emplace_back(f, f);
    else
      boxes.emplace_back(p.bbox() + q.bbox() + r.bbox(), f);
  }
  std::vector<const Box*> ptrs;
  ptrs.reserve(boxes.size());
  for (auto& b : boxes) ptrs.push_back(&b);
  auto cb = [&](const Box* x, const Box* y) {
    if (soup_faces_intersect(s, x->info(), y->info())) out.emplace_back(x->info(), y->info());
  };
  CGAL::box_self_intersection_d<CGAL::Sequential_tag>(ptrs.begin(), ptrs.end(), cb, std::ptrdiff_t(2000));
  return out;
}

// ------------------------------------------------------------------ topology
struct Topo {
  long V = 0, F = 0, E = 0, isolated = 0, borders = 0, components = 0, chi = 0, genus = 0;
};

// Per-component sums -> genus; comp ids 0..ncomp-1.
long genus_from(const std::vector<long>& v, const std::vector<long>& e, const std::vector<long>& f,
                const std::vector<long>& b) {
  long g = 0;
  for (std::size_t c = 0; c < v.size(); ++c) {
    long two_g = 2 - (v[c] - e[c] + f[c]) - b[c];
    if (two_g < 0 || two_g % 2 != 0) return -1;
    g += two_g / 2;
  }
  return g;
}

std::string topo_str(const Topo& t) {
  std::ostringstream o;
  o << "V=" << t.V << " F=" << t.F << " E=" << t.E << " isolated=" << t.isolated
    << " borders=" << t.borders << " components=" << t.components << " chi=" << t.chi
    << " genus=" << t.genus;
  return o.str();
}

Topo openmesh_topology(const std::string& path) {
  OMesh m;
  OpenMesh::IO::Options opt;
  if (!OpenMesh::IO::read_mesh(m, path, opt)) throw Error("OpenMesh cannot read the file");
  Topo t;
  t.V = long(m.n_vertices());
  t.F = long(m.n_faces());
  t.E = long(m.n_edges());
  // union-find over vertices joined by faces
  std::vector<int> parent(m.n_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (auto f : m.faces()) {
    int first = -1;
    for (auto v : m.fv_range(f)) {
      if (first < 0)
        first = v.idx();
      else
        parent[find(v.idx())] = find(first);
    }
  }
  std::vector<int> comp(m.n_vertices(), -1);
  int ncomp = 0;
  std::map<int, int> root_id;
  for (auto v : m.vertices()) {
    if (m.is_isolated(v)) {
      ++t.isolated;
      continue;
    }
    int r = find(v.idx());
    auto it = root_id.find(r);
    if (it == root_id.end()) it = root_id.emplace(r, ncomp++).first;
    comp[v.idx()] = it->second;
  }
  std::vector<long> cv(ncomp, 0), ce(ncomp, 0), cf(ncomp, 0), cb(ncomp, 0);
  for (auto v : m.vertices())
    if (comp[v.idx()] >= 0) ++cv[comp[v.idx()]];
  for (auto e : m.edges()) ++ce[comp[m.to_vertex_handle(m.halfedge_handle(e, 0)).idx()]];
  for (auto f : m.faces()) ++cf[comp[m.to_vertex_handle(m.halfedge_handle(f)).idx()]];
  std::vector<char> seen(m.n_halfedges(), 0);
  for (auto h : m.halfedges()) {
    if (!m.is_boundary(h) || seen[h.idx()]) continue;
    ++t.borders;
    ++cb[comp[m.to_vertex_handle(h).idx()]];
    auto g = h;
    std::size_t guard = 0;
    do {
      seen[g.idx()] = 1;
      g = m.next_halfedge_handle(g);
      if (++guard > m.n_halfedges()) throw Error("OpenMesh boundary walk does not close");
    } while (g != h);
  }
  t.components = ncomp;
  t.chi = (t.V - t.isolated) - t.E + t.F;
  t.genus = genus_from(cv, ce, cf, cb);
  return t;
}

Topo cgal_topology(Mesh& m) {
  Topo t;
  t.V = long(m.number_of_vertices());
  t.F = long(m.number_of_faces());
  t.E = long(m.number_of_edges());
  auto fcc = m.add_property_map<face_descriptor, std::size_t>("f:cc", 0).first;
  std::size_t ncomp = PMP::connected_components(m, fcc);
  std::vector<long> cv(ncomp, 0), ce(ncomp, 0), cf(ncomp, 0), cb(ncomp, 0);
  for (auto v : m.vertices()) {
    if (m.is_isolated(v)) {
      ++t.isolated;
      continue;
    }
    halfedge_descriptor h = m.halfedge(v);
    if (m.is_border(h)) h = m.opposite(h);
    ++cv[fcc[m.face(h)]];
  }
  for (auto e : m.edges()) {
    halfedge_descriptor h = m.halfedge(e);
    if (m.is_border(h)) h = m.opposite(h);
    ++ce[fcc[m.face(h)]];
  }
  for (auto f : m.faces()) ++cf[fcc[f]];
  std::vector<halfedge_descriptor> cycles;
  PMP::extract_boundary_cycles(m, std::back_inserter(cycles));
  for (auto h : cycles) ++cb[fcc[m.face(m.opposite(h))]];
  t.borders = long(cycles.size());
  t.components = long(ncomp);
  t.chi = (t.V - t.isolated) - t.E + t.F;
  t.genus = genus_from(cv, ce, cf, cb);
  return t;
}

// ------------------------------------------------------------------ request handling
struct Out {
  std::ostream& os;
  void ok(const std::string& cmd, std::size_t n, const std::string& extra = "") {
    os << "ok " << cmd << ' ' << n;
    if (!extra.empty()) os << ' ' << extra;
    os << '\n';
  }
  void err(const std::string& cmd, const std::string& msg) {
    std::string m = msg;
    for (char& c : m)
      if (c == '\n' || c == '\r') c = ' ';
    os << "err " << cmd << ' ' << m << '\n';
  }
};

// Reads the body lines of a batch; parse errors are remembered, the body is always consumed.
std::vector<std::vector<double>> read_batch(Input& in, long n, std::size_t width, std::string& error) {
  std::vector<std::vector<double>> rows;
  rows.reserve(std::size_t(n));
  std::string line;
  for (long i = 0; i < n; ++i) {
    if (!in.next_line(line)) {
      if (error.empty()) error = "input ended inside the batch at row " + std::to_string(i);
      break;
    }
    if (!error.empty()) continue;
    try {
      rows.push_back(parse_nums(line, width));
    } catch (const std::exception& e) {
      error = "row " + std::to_string(i) + ": " + e.what();
    }
  }
  return rows;
}

std::vector<std::string> read_paths(Input& in, int n) {
  std::vector<std::string> v;
  std::string line;
  for (int i = 0; i < n; ++i) {
    if (!in.next_line(line)) throw Error("missing path line");
    v.push_back(line);
  }
  return v;
}

P3 p3(const std::vector<double>& r, std::size_t i) { return P3(r[i], r[i + 1], r[i + 2]); }
EK::Point_3 ep3(const std::vector<double>& r, std::size_t i) {
  return EK::Point_3(r[i], r[i + 1], r[i + 2]);
}

void handle_batch(const std::string& cmd, const std::vector<std::string>& args, Input& in, Out& out) {
  std::size_t width = 0;
  if (cmd == "orient3d") width = 12;
  else if (cmd == "orient2d") width = 6;
  else if (cmd == "tri_tri") width = 18;
  else if (cmd == "seg_tri") width = 15;
  else if (cmd == "point_tri_sqdist") width = 13;
  if (args.size() != 1) throw Error("usage: " + cmd + " N");
  long n = parse_count(args[0]);
  std::string error;
  auto rows = read_batch(in, n, width, error);
  if (!error.empty()) throw Error(error);
  std::string body;
  body.reserve(rows.size() * 3);
  for (const auto& r : rows) {
    int a = 0;
    if (cmd == "orient3d") {
      a = int(CGAL::orientation(p3(r, 0), p3(r, 3), p3(r, 6), p3(r, 9)));
    } else if (cmd == "orient2d") {
      a = int(CGAL::orientation(P2(r[0], r[1]), P2(r[2], r[3]), P2(r[4], r[5])));
    } else if (cmd == "tri_tri") {
      a = simplices_intersect(make_simplex<K>(p3(r, 0), p3(r, 3), p3(r, 6)),
                              make_simplex<K>(p3(r, 9), p3(r, 12), p3(r, 15)));
    } else if (cmd == "seg_tri") {
      a = simplices_intersect(make_simplex<K>(p3(r, 0), p3(r, 3)),
                              make_simplex<K>(p3(r, 6), p3(r, 9), p3(r, 12)));
    } else {
      EK::FT d = sqdist_point_simplex(ep3(r, 0), make_simplex<EK>(ep3(r, 3), ep3(r, 6), ep3(r, 9)));
      a = int(CGAL::compare(d, EK::FT(r[12])));
    }
    body += std::to_string(a);
    body += '\n';
  }
  out.ok(cmd, rows.size());
  out.os << body;
}

void handle(const std::string& header, Input& in, Out& out) {
  std::vector<std::string> toks = split_ws(header);
  const std::string cmd = toks[0];
  std::vector<std::string> args(toks.begin() + 1, toks.end());
  try {
    if (cmd == "orient3d" || cmd == "orient2d" || cmd == "tri_tri" || cmd == "seg_tri" ||
        cmd == "point_tri_sqdist") {
      handle_batch(cmd, args, in, out);
    } else if (cmd == "version") {
      out.ok(cmd, 0, std::string("protocol=1 cgal=") + CGAL_VERSION_STR + " openmesh=" +
                         std::to_string(OM_GET_VER) + "." + std::to_string(OM_GET_MAJ));
    } else if (cmd == "self_intersections") {
      bool force_soup = false, time_only = false;
      for (const auto& a : args) {
        if (a == "--soup") force_soup = true;
        else if (a == "--time") time_only = true;
        else throw Error("unknown option '" + a + "'");
      }
      std::string path = read_paths(in, 1)[0];
      auto t0 = std::chrono::steady_clock::now();
      Soup s = read_soup(path);
      require_triangles(s);
      Mesh m;
      bool is_mesh = !force_soup && soup_to_mesh(s, m);
      auto t1 = std::chrono::steady_clock::now();
      std::string kind = std::string("kind=") + (is_mesh ? "mesh" : "soup");
      if (time_only) {
        bool any;
        auto t2 = std::chrono::steady_clock::now();
        if (is_mesh) any = PMP::does_self_intersect<CGAL::Sequential_tag>(m);
        else any = !soup_self_intersections(s).empty();
        auto t3 = std::chrono::steady_clock::now();
        std::chrono::duration<double> secs = t3 - t2, load = t1 - t0;
        out.ok("self_intersections_time", 0,
               kind + " intersects=" + (any ? "1" : "0") + " seconds=" + decf(secs.count()) +
                   " load_seconds=" + decf(load.count()));
        return;
      }
      std::vector<std::pair<std::size_t, std::size_t>> pairs;
      if (is_mesh) {
        std::vector<std::pair<face_descriptor, face_descriptor>> fp;
        PMP::self_intersections<CGAL::Sequential_tag>(m, std::back_inserter(fp));
        for (auto& p : fp) pairs.emplace_back(std::size_t(p.first), std::size_t(p.second));
      } else {
        pairs = soup_self_intersections(s);
      }
      for (auto& p : pairs)
        if (p.first > p.second) std::swap(p.first, p.second);
      std::sort(pairs.begin(), pairs.end());
      pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
      out.ok(cmd, pairs.size(),
             kind + " vertices=" + std::to_string(s.pts.size()) + " faces=" + std::to_string(s.polys.size()));
      for (auto& p : pairs) out.os << p.first << ' ' << p.second << '\n';
    } else if (cmd == "hausdorff" || cmd == "hausdorff_approx") {
      if (args.size() != 1) throw Error("usage: " + cmd + (cmd == "hausdorff" ? " ERROR_BOUND" : " POINTS"));
      auto paths = read_paths(in, 2);
      double param = parse_num(args[0]);
      Mesh a = load_triangle_mesh(paths[0]);
      Mesh b = load_triangle_mesh(paths[1]);
      double d;
      if (cmd == "hausdorff") {
        if (!(param > 0)) throw Error("error bound must be > 0");
        d = PMP::bounded_error_Hausdorff_distance<CGAL::Sequential_tag>(a, b, param);
      } else {
        if (!(param >= 1)) throw Error("point count must be >= 1");
        d = PMP::approximate_Hausdorff_distance<CGAL::Sequential_tag>(
            a, b, CGAL::parameters::number_of_points_on_faces(std::size_t(param)).random_seed(0),
            CGAL::parameters::default_values());
      }
      out.ok(cmd, 0, "distance=" + hexf(d) + " decimal=" + decf(d));
    } else if (cmd == "topology") {
      if (!args.empty()) throw Error("usage: topology (path on the next line)");
      std::string path = read_paths(in, 1)[0];
      std::string om_line, cg_line;
      long file_polys = -1;
      std::string cg;
      try {
        Soup s = read_soup(path);
        file_polys = long(s.polys.size());
        Mesh m;
        if (soup_to_mesh(s, m)) {
          cg = "cgal loaded=1 kind=mesh " + topo_str(cgal_topology(m));
        } else {
          cg = "cgal loaded=0 kind=soup V=" + std::to_string(s.pts.size()) +
               " F=" + std::to_string(s.polys.size());
        }
      } catch (const std::exception& e) {
        std::string msg = e.what();
        std::replace(msg.begin(), msg.end(), ' ', '_');
        cg = "cgal loaded=0 error=" + msg;
      }
      std::string om;
      try {
        om = "openmesh loaded=1 " + topo_str(openmesh_topology(path)) +
             " file_polygons=" + std::to_string(file_polys);
      } catch (const std::exception& e) {
        std::string msg = e.what();
        std::replace(msg.begin(), msg.end(), ' ', '_');
        om = "openmesh loaded=0 error=" + msg;
      }
      out.ok(cmd, 2);
      out.os << om << '\n' << cg << '\n';
    } else {
      throw Error("unknown command");
    }
  } catch (const std::exception& e) {
    out.err(cmd, e.what());
  }
}

void serve(std::istream& is, std::ostream& os) {
  Input in(is);
  Out out{os};
  std::string line;
  while (in.next_line(line)) {
    std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    handle(line, in, out);
    os.flush();
  }
}

int usage() {
  std::cerr << "usage: envelope-oracle [serve]            (stdin protocol, see README.md)\n"
               "       envelope-oracle topology FILE\n"
               "       envelope-oracle self_intersections [--soup] [--time] FILE\n"
               "       envelope-oracle hausdorff FILE_A FILE_B ERROR_BOUND\n"
               "       envelope-oracle hausdorff_approx FILE_A FILE_B POINTS_ON_FACES\n"
               "       envelope-oracle version\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::ios::sync_with_stdio(false);
  // OpenMesh logs to stdout/stderr; stdout is the protocol channel, so silence it.
  omout().disable();
  omlog().disable();
  omerr().disable();

  std::vector<std::string> a(argv + 1, argv + argc);
  if (a.empty() || (a.size() == 1 && a[0] == "serve")) {
    serve(std::cin, std::cout);
    return std::cin.bad() ? 1 : 0;
  }
  std::string req;
  const std::string& cmd = a[0];
  if (cmd == "--help" || cmd == "-h") return usage(), 0;
  if (cmd == "topology" && a.size() == 2) {
    req = "topology\n" + a[1] + "\n";
  } else if (cmd == "self_intersections" && a.size() >= 2) {
    req = "self_intersections";
    for (std::size_t i = 1; i + 1 < a.size(); ++i) req += " " + a[i];
    req += "\n" + a.back() + "\n";
  } else if ((cmd == "hausdorff" || cmd == "hausdorff_approx") && a.size() == 4) {
    req = cmd + " " + a[3] + "\n" + a[1] + "\n" + a[2] + "\n";
  } else if (cmd == "version" && a.size() == 1) {
    req = "version\n";
  } else {
    return usage();
  }
  std::istringstream is(req);
  std::ostringstream os;
  serve(is, os);
  std::cout << os.str();
  return os.str().rfind("err", 0) == 0 ? 1 : 0;
}
