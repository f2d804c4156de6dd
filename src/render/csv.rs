//! The answer as a table: one row per speed, time or pole, each column's unit in its header
//! (`speed [rad/s]`, or the answer's `output_unit`; `phase [rad]`; `[-]` for a ratio).

use crate::answer::Output;
use crate::model::api::SpeedUnit;

fn num(v: Option<f64>) -> String {
    v.map(|x| format!("{x}")).unwrap_or_default()
}

/// The result as a table: one row per speed, time or pole.
pub fn csv(out: &Output) -> Option<String> {
    let mut s = String::new();
    match out {
        Output::Modal(m) => {
            s.push_str(
                "decay_rate [1/s],frequency [rad/s],whirl,damping_ratio [-],log_decrement [-],\
                 whirl_ratio [-]\n",
            );
            for p in &m.poles {
                let whirl = serde_json::to_value(p.whirl).ok()?.as_str()?.to_string();
                s.push_str(&format!(
                    "{},{},{whirl},{},{},{}\n",
                    p.decay_rate,
                    p.frequency,
                    p.damping_ratio,
                    num(p.log_decrement),
                    num(p.whirl_ratio)
                ));
            }
        }
        Output::Campbell(c) => {
            s.push_str("speed [rad/s]");
            for b in &c.branches {
                let w = if b.whirl == crate::model::api::Whirl::Forward {
                    "forward"
                } else {
                    "backward"
                };
                for q in [
                    "frequency [rad/s]",
                    "decay_rate [1/s]",
                    "log_decrement [-]",
                    "damping_ratio [-]",
                    "whirl_ratio [-]",
                ] {
                    s.push_str(&format!(",mode{}_{w}_{q}", b.mode));
                }
            }
            s.push('\n');
            for (i, w) in c.speeds.iter().enumerate() {
                s.push_str(&format!("{w}"));
                for b in &c.branches {
                    s.push_str(&format!(
                        ",{},{},{},{},{}",
                        num(b.frequency[i]),
                        num(b.decay_rate[i]),
                        num(b.log_decrement[i]),
                        num(b.damping_ratio[i]),
                        num(b.whirl_ratio[i])
                    ));
                }
                s.push('\n');
            }
        }
        Output::Stability(st) => {
            s.push_str("speed [rad/s],max_decay_rate [1/s]\n");
            for (w, d) in st.speeds.iter().zip(&st.max_decay_rate) {
                s.push_str(&format!("{w},{d}\n"));
            }
        }
        Output::Time(t) => {
            s.push_str("time [s]");
            for n in &t.nodes {
                s.push_str(&format!(",node{}_x [m],node{}_y [m]", n.node, n.node));
            }
            s.push('\n');
            for (i, time) in t.time.iter().enumerate() {
                s.push_str(&format!("{time}"));
                for n in &t.nodes {
                    s.push_str(&format!(",{},{}", n.x[i], n.y[i]));
                }
                s.push('\n');
            }
        }
        Output::Unbalance(u) => {
            s.push_str("speed [rad/s]");
            for n in &u.nodes {
                for c in [
                    "amplitude [m]",
                    "phase [rad]",
                    "x_amplitude [m]",
                    "x_phase [rad]",
                    "y_amplitude [m]",
                    "y_phase [rad]",
                    "major [m]",
                    "minor [m]",
                ] {
                    s.push_str(&format!(",node{}_{c}", n.node));
                }
            }
            s.push('\n');
            for (i, w) in u.speeds.iter().enumerate() {
                s.push_str(&format!("{w}"));
                for n in &u.nodes {
                    for c in [
                        &n.amplitude,
                        &n.phase,
                        &n.x_amplitude,
                        &n.x_phase,
                        &n.y_amplitude,
                        &n.y_phase,
                        &n.major,
                        &n.minor,
                    ] {
                        s.push_str(&format!(",{}", c[i]));
                    }
                }
                s.push('\n');
            }
        }
        Output::CriticalMap(c) => {
            s.push_str("stiffness [N/m]");
            for k in 1..=c.frequencies.len() {
                s.push_str(&format!(",mode{k}_frequency [rad/s]"));
            }
            s.push('\n');
            for (i, k) in c.stiffness.iter().enumerate() {
                s.push_str(&format!("{k}"));
                for f in &c.frequencies {
                    s.push_str(&format!(",{}", f[i]));
                }
                s.push('\n');
            }
        }
        Output::Static(st) => {
            s.push_str(
                "node,position [m],deflection [m],deflection_x [m],slope [rad],slope_x [rad],\
                 reaction [N],reaction_x [N],shear_left [N],shear_right [N],bending_moment [N m]\n",
            );
            // Shear left and right of a node (it jumps by the node's forces), moment there.
            let left = |k: usize| st.stations.iter().rfind(|t| t.element + 1 == k);
            let right = |k: usize| st.stations.iter().find(|t| t.element == k);
            for (k, n) in st.nodes.iter().enumerate() {
                let r = st.supports.iter().filter(|r| r.node == n.node);
                let (ry, rx) = r.fold((None, None), |(y, x), r| {
                    (
                        Some(y.unwrap_or(0.0) + r.reaction),
                        Some(x.unwrap_or(0.0) + r.reaction_x),
                    )
                });
                let (l, r) = (left(k), right(k));
                let moment = r.or(l).map(|t| t.bending_moment);
                s.push_str(&format!(
                    "{},{},{},{},{},{},{},{},{},{},{}\n",
                    n.node,
                    n.position,
                    n.deflection,
                    n.deflection_x,
                    n.slope,
                    n.slope_x,
                    num(ry),
                    num(rx),
                    num(l.map(|t| t.shear)),
                    num(r.map(|t| t.shear)),
                    num(moment)
                ));
            }
        }
        Output::Level1(l) => {
            s.push_str("cross_coupling [N/m],log_decrement [-],frequency [rad/s]\n");
            for (i, q) in l.cross_coupling.iter().enumerate() {
                s.push_str(&format!(
                    "{q},{},{}\n",
                    num(l.log_decrement[i]),
                    num(l.frequency[i])
                ));
            }
        }
        Output::Frequency(f) => {
            s.push_str(
                "frequency [rad/s],amplitude [m/N],phase [rad],x_amplitude [m/N],x_phase [rad],\
                 y_amplitude [m/N],y_phase [rad],forward [m/N],backward [m/N]\n",
            );
            for i in 0..f.frequencies.len() {
                s.push_str(&format!(
                    "{},{},{},{},{},{},{},{},{}\n",
                    f.frequencies[i],
                    f.amplitude[i],
                    f.phase[i],
                    f.x_amplitude[i],
                    f.x_phase[i],
                    f.y_amplitude[i],
                    f.y_phase[i],
                    f.forward[i],
                    f.backward[i]
                ));
            }
        }
        Output::Damping(_) | Output::Report(_) => return None,
    }
    // Speeds and frequencies are in the answer's unit: the header says which.
    let unit = out.unit();
    if unit != SpeedUnit::RadPerSecond {
        let end = s.find('\n').unwrap_or(s.len());
        let header = s[..end].replace("[rad/s]", &format!("[{}]", unit.symbol()));
        s.replace_range(..end, &header);
    }
    Some(s)
}
