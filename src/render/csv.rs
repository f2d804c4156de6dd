//! The answer as a table: one row per speed, time or pole.

use crate::answer::Output;

fn num(v: Option<f64>) -> String {
    v.map(|x| format!("{x}")).unwrap_or_default()
}

/// The result as a table: one row per speed, time or pole.
pub fn csv(out: &Output) -> Option<String> {
    let mut s = String::new();
    match out {
        Output::Modal(m) => {
            s.push_str("decay_rate,frequency,whirl,damping_ratio,log_decrement,whirl_ratio\n");
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
            s.push_str("speed");
            for b in &c.branches {
                let w = if b.whirl == crate::model::api::Whirl::Forward {
                    "forward"
                } else {
                    "backward"
                };
                for q in [
                    "frequency",
                    "decay_rate",
                    "log_decrement",
                    "damping_ratio",
                    "whirl_ratio",
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
            s.push_str("speed,max_decay_rate\n");
            for (w, d) in st.speeds.iter().zip(&st.max_decay_rate) {
                s.push_str(&format!("{w},{d}\n"));
            }
        }
        Output::Time(t) => {
            s.push_str("time");
            for n in &t.nodes {
                s.push_str(&format!(",node{}_x,node{}_y", n.node, n.node));
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
            s.push_str("speed");
            for n in &u.nodes {
                for c in [
                    "amplitude",
                    "phase",
                    "x_amplitude",
                    "x_phase",
                    "y_amplitude",
                    "y_phase",
                    "major",
                    "minor",
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
            s.push_str("stiffness");
            for k in 1..=c.frequencies.len() {
                s.push_str(&format!(",mode{k}_frequency"));
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
                "node,position,deflection,deflection_x,slope,slope_x,reaction,reaction_x,\
                 shear_left,shear_right,bending_moment\n",
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
            s.push_str("cross_coupling,log_decrement,frequency\n");
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
                "frequency,amplitude,phase,x_amplitude,x_phase,y_amplitude,y_phase,forward,\
                 backward\n",
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
    Some(s)
}
