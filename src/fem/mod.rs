//! Finite elements: the Timoshenko shaft element, assembly of a beam rotor, Guyan reduction,
//! and the undamped modal basis.

pub mod assembly;
pub mod conical;
pub mod element;
pub mod guyan;
pub mod modal;
pub mod train;
