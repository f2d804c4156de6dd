//! Gear meshes: the element joining two shafts of a train that turn at different speeds.

use super::api::{GearInput, SegmentInput};
use super::error::{Invalid, non_negative, positive};

/// A validated gear mesh (see `api::GearInput`).
#[derive(Debug, Clone, PartialEq)]
pub struct Gear {
    pub length: f64,
    pub outer_diameter: f64,
    /// Speed of the driven shaft over the driving one's.
    pub ratio: f64,
    /// Referred to the driving shaft, N m/rad and N m s/rad.
    pub mesh_stiffness: f64,
    pub mesh_damping: f64,
    /// N/m.
    pub axial_stiffness: f64,
}

impl Gear {
    /// The gear of segment `seg` at `at` (`rotor.shaft[i]`).
    pub fn parse(seg: &SegmentInput, g: &GearInput, at: &str, bad: &mut Invalid) -> Option<Self> {
        super::coupling::refuse_section(
            seg,
            at,
            "a gear mesh is one element without a section: give it `length`, `outer_diameter` \
             (drawn) and `gear` only (each gear's inertia a disk)",
            bad,
        );
        let length = bad.check(&format!("{at}.length"), positive(seg.length));
        let outer = bad.check(
            &format!("{at}.outer_diameter"),
            positive(seg.outer_diameter),
        );
        let at = format!("{at}.gear");
        let ratio = bad.check(
            &format!("{at}.ratio"),
            positive(g.ratio).and_then(|r| {
                if (1e-3..=1e3).contains(&r) {
                    Ok(r)
                } else {
                    Err(format!("must be between 0.001 and 1000 (got {r})"))
                }
            }),
        );
        let k = bad.check(&format!("{at}.mesh_stiffness"), positive(g.mesh_stiffness));
        let c = bad.check(&format!("{at}.mesh_damping"), non_negative(g.mesh_damping));
        let ka = bad.check(
            &format!("{at}.axial_stiffness"),
            non_negative(g.axial_stiffness),
        );
        Some(Gear {
            length: length?,
            outer_diameter: outer?,
            ratio: ratio?,
            mesh_stiffness: k?,
            mesh_damping: c?,
            axial_stiffness: ka?,
        })
    }
}
