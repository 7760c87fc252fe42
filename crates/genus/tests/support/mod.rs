pub mod voxel_closing;
