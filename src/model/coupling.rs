//! Flexible couplings: the element joining the shafts of a train.
//!
//! A coupling between nodes `l` and `r = l + 1` holds springs `k_t` between their translations
//! and `k_r` between their rotations, with dampers `c_t`, `c_r` beside them, and the masses and
//! inertias of its two halves lumped on the two nodes (ROSS's `CouplingElement`, lateral part:
//! for a displacement `u_l`, `u_r` of either pair the force on `l` is `k (u_r - u_l)`). It turns
//! with the shafts: its dampers are rotating damping, and its loss factor rotating hysteretic
//! damping of its springs.

use super::api::{CouplingInput, SegmentInput};
use super::error::{Invalid, loss_factor, non_negative, positive};

/// A validated coupling.
#[derive(Debug, Clone, PartialEq)]
pub struct Coupling {
    /// Axial length, m: places the nodes after it.
    pub length: f64,
    /// Drawn diameter, m.
    pub outer_diameter: f64,
    pub translational_stiffness: f64,
    pub angular_stiffness: f64,
    pub translational_damping: f64,
    pub angular_damping: f64,
    pub loss_factor: f64,
    /// `[left, right]`, kg.
    pub mass: [f64; 2],
    /// `[left, right]`, kg m^2.
    pub polar_inertia: [f64; 2],
    pub transverse_inertia: [f64; 2],
    /// N m/rad and N m s/rad.
    pub torsional_stiffness: f64,
    pub torsional_damping: f64,
    /// N/m and N s/m.
    pub axial_stiffness: f64,
    pub axial_damping: f64,
}

impl Coupling {
    /// Both halves' mass, kg.
    pub fn total_mass(&self) -> f64 {
        self.mass[0] + self.mass[1]
    }

    /// The coupling of segment `seg` at `at` (`rotor.shaft[i]`), refusing the fields a shaft
    /// segment has and a coupling does not.
    pub fn parse(
        seg: &SegmentInput,
        c: &CouplingInput,
        at: &str,
        bad: &mut Invalid,
    ) -> Option<Self> {
        refuse_section(
            seg,
            at,
            "a coupling is one element without a section: give it `length`, `outer_diameter` \
             (drawn) and `coupling` only",
            bad,
        );
        let length = bad.check(&format!("{at}.length"), positive(seg.length));
        let outer = bad.check(
            &format!("{at}.outer_diameter"),
            positive(seg.outer_diameter),
        );
        let at = format!("{at}.coupling");
        let mut field = |name: &str, v: f64| bad.check(&format!("{at}.{name}"), non_negative(v));
        let kt = field("translational_stiffness", c.translational_stiffness);
        let kr = field("angular_stiffness", c.angular_stiffness);
        let ct = field("translational_damping", c.translational_damping);
        let cr = field("angular_damping", c.angular_damping);
        let kz = field("torsional_stiffness", c.torsional_stiffness);
        let cz = field("torsional_damping", c.torsional_damping);
        let ka = field("axial_stiffness", c.axial_stiffness);
        let ca = field("axial_damping", c.axial_damping);
        let pair = |bad: &mut Invalid, name: &str, v: [f64; 2]| -> Option<[f64; 2]> {
            let l = bad.check(&format!("{at}.{name}[0]"), non_negative(v[0]));
            let r = bad.check(&format!("{at}.{name}[1]"), non_negative(v[1]));
            Some([l?, r?])
        };
        let mass = pair(bad, "mass", c.mass);
        let ip = pair(bad, "polar_inertia", c.polar_inertia);
        let id = match c.transverse_inertia {
            Some(v) => pair(bad, "transverse_inertia", v),
            None => ip.map(|[l, r]| [l / 2.0, r / 2.0]),
        };
        let eta = bad.check(&format!("{at}.loss_factor"), loss_factor(c.loss_factor));
        Some(Coupling {
            length: length?,
            outer_diameter: outer?,
            translational_stiffness: kt?,
            angular_stiffness: kr?,
            translational_damping: ct?,
            angular_damping: cr?,
            loss_factor: eta?,
            mass: mass?,
            polar_inertia: ip?,
            transverse_inertia: id?,
            torsional_stiffness: kz?,
            torsional_damping: cz?,
            axial_stiffness: ka?,
            axial_damping: ca?,
        })
    }
}

/// Refuses, with `message`, the fields a shaft segment has and an element without a section (a
/// coupling, a gear mesh) does not.
pub fn refuse_section(seg: &SegmentInput, at: &str, message: &str, bad: &mut Invalid) {
    let shaft_only: [(&str, bool); 12] = [
        ("shear_effects", seg.shear_effects.is_some()),
        ("rotary_inertia", seg.rotary_inertia.is_some()),
        ("gyroscopic", seg.gyroscopic.is_some()),
        ("material", !seg.material.is_empty()),
        ("inner_diameter", seg.inner_diameter != 0.0),
        ("elements", seg.elements.is_some_and(|n| n != 1)),
        ("shear_factor", seg.shear_factor.is_some()),
        ("outer_diameter_right", seg.outer_diameter_right.is_some()),
        ("inner_diameter_right", seg.inner_diameter_right.is_some()),
        ("axial_force", seg.axial_force.is_some()),
        ("torque", seg.torque.is_some()),
        ("rayleigh_damping", seg.rayleigh_damping.is_some()),
    ];
    for (field, given) in shaft_only {
        if given {
            bad.push(format!("{at}.{field}"), message);
        }
    }
}
