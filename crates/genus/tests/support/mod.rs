pub mod prisms;
pub mod voxel_closing;
