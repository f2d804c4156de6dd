//! The Jeffcott (Laval) rotor, validated.

use super::api::JeffcottInput;
use super::error::{Invalid, loss_factor, non_negative, positive};

/// Jeffcott rotor: mass `m` on an isotropic shaft of stiffness `k`, with rotating and
/// nonrotating viscous damping and hysteretic loss factors.
#[derive(Debug, Clone, PartialEq)]
pub struct Jeffcott {
    mass: f64,
    stiffness: f64,
    loss_factor_rotating: f64,
    loss_factor_nonrotating: f64,
    damping_rotating: f64,
    damping_nonrotating: f64,
}

impl Jeffcott {
    /// The paper's nondimensional rotor (mass = stiffness = 1): speeds in units of sqrt(k/m).
    pub fn is_nondimensional(&self) -> bool {
        self.mass == 1.0 && self.stiffness == 1.0
    }

    pub fn parse(j: &JeffcottInput, at: &str) -> Result<Self, Invalid> {
        let mut bad = Invalid::default();
        let mass = bad.check(&format!("{at}.mass"), positive(j.mass));
        let stiffness = bad.check(&format!("{at}.stiffness"), positive(j.stiffness));
        let eta_r = bad.check(
            &format!("{at}.loss_factor_rotating"),
            loss_factor(j.loss_factor_rotating),
        );
        let eta_n = bad.check(
            &format!("{at}.loss_factor_nonrotating"),
            loss_factor(j.loss_factor_nonrotating),
        );
        let c_r = bad.check(
            &format!("{at}.damping_rotating"),
            non_negative(j.damping_rotating),
        );
        let c_n = bad.check(
            &format!("{at}.damping_nonrotating"),
            non_negative(j.damping_nonrotating),
        );
        bad.into_result(|| Jeffcott {
            mass: mass.unwrap(),
            stiffness: stiffness.unwrap(),
            loss_factor_rotating: eta_r.unwrap(),
            loss_factor_nonrotating: eta_n.unwrap(),
            damping_rotating: c_r.unwrap(),
            damping_nonrotating: c_n.unwrap(),
        })
    }

    /// The paper's nondimensional rotor (`m = k = 1`) with the given loss factors.
    pub fn nondimensional(eta_r: f64, eta_n: f64) -> Result<Self, Invalid> {
        Self::parse(
            &JeffcottInput {
                mass: 1.0,
                stiffness: 1.0,
                loss_factor_rotating: eta_r,
                loss_factor_nonrotating: eta_n,
                damping_rotating: 0.0,
                damping_nonrotating: 0.0,
            },
            "rotor",
        )
    }

    pub fn mass(&self) -> f64 {
        self.mass
    }
    pub fn stiffness(&self) -> f64 {
        self.stiffness
    }
    pub fn loss_factor_rotating(&self) -> f64 {
        self.loss_factor_rotating
    }
    pub fn loss_factor_nonrotating(&self) -> f64 {
        self.loss_factor_nonrotating
    }
    pub fn damping_rotating(&self) -> f64 {
        self.damping_rotating
    }
    pub fn damping_nonrotating(&self) -> f64 {
        self.damping_nonrotating
    }
}
