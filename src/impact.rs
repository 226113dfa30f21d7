//! The impact models (`golf_physics::impact`), with the one step the IO-free physics crate leaves to impactd:
//! reading a soil file named by `--soil` or a rig's `soil` (size-capped, [`crate::capped`]).

pub use golf_physics::impact::*;

/// The continuous models (`golf_physics::impact::continuous`).
pub mod continuous {
    pub use golf_physics::impact::continuous::*;

    /// The iron-and-ground model (`golf_physics::impact::continuous::iron_ground`).
    pub mod iron_ground {
        pub use golf_physics::impact::continuous::iron_ground::*;

        /// The ground model's club file sections (`golf_physics::impact::continuous::iron_ground::sections`).
        pub mod sections {
            pub use golf_physics::impact::continuous::iron_ground::sections::*;

            use crate::capped::{read_to_string, MAX_INPUT_FILE_BYTES};
            use golf_physics::impact::ImpactError;

            /// The `[soil]` section a `--soil` or daemon `soil` value stands for: a preset, a soil file (read
            /// here, at most [`MAX_INPUT_FILE_BYTES`]), or `none`.
            pub fn soil_arg_section(name_or_path: &str) -> Result<toml::Table, ImpactError> {
                soil_arg_section_with(name_or_path, &|path| read_to_string(path, MAX_INPUT_FILE_BYTES))
            }
        }
    }
}
