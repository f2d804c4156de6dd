//! The analyses of a rotordynamic audit (API 684 / API 617): the undamped critical speed map
//! ([`critical_map`]), static deflection and bearing loads ([`statics`], the curve between nodes by [`deflection`]), the Level I stability
//! screen ([`level1`]) and the Level II analysis ([`level2`]), the non-synchronous frequency response ([`frequency`]) and the
//! resonance peaks of a response curve with their amplification factors and separation
//! margins ([`peaks`]). The report's unbalance cases are placed by API 684's rules
//! ([`placement`]) and run and read against API 617's limits ([`cases`]).

pub mod cases;
pub mod critical_map;
pub mod deflection;
pub mod frequency;
pub mod level1;
pub mod level1_reduced;
pub mod level2;
pub mod peaks;
pub mod placement;
pub mod statics;
