//! Finite-element side of the model: modal bases (and, as rotors grow, element matrices,
//! assembly and Guyan reduction).

pub mod modal;
