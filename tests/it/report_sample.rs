//! Hand-built answers of the audit analyses for a realistic rotor, shared by the report_*
//! tests (included with `#[path]`; alone it is an empty test target): a 1.5 m steel shaft of
//! 50 mm (40 mm journals), a 32.6 kg disk at mid-span, bearings of 1e6 and 1.5e6/2e6 N/m (first
//! critical ~123 rad/s), operating 180..300 rad/s; and readers of the SVG they render to.
#![allow(dead_code)]

use std::collections::BTreeMap;

use whirl::model::api::*;

pub const RPM: f64 = 60.0 / (2.0 * std::f64::consts::PI);
pub const G: f64 = 9.8065;
pub const E: f64 = 2.11e11;
pub const RHO: f64 = 7810.0;

pub fn rotor() -> RotorInput {
    let seg = |length: f64, d: f64, elements: i64| SegmentInput {
        length,
        outer_diameter: d,
        inner_diameter: 0.0,
        material: "steel".into(),
        elements: Some(elements),
        ..Default::default()
    };
    let steel = MaterialInput {
        young_modulus: E,
        density: RHO,
        poisson_ratio: 0.3,
        loss_factor: 0.002,
    };
    RotorInput::Beam(BeamInput {
        materials: BTreeMap::from([("steel".to_string(), steel)]),
        shaft: vec![seg(0.1, 0.04, 1), seg(1.3, 0.05, 8), seg(0.1, 0.04, 1)],
        disks: vec![DiskInput {
            node: 5,
            mass: 32.6,
            polar_inertia: 0.178,
            transverse_inertia: 0.0977,
        }],
        seals: vec![],
        point_masses: vec![],
        sleeves: vec![],
        supports: vec![
            SupportInput {
                node: 1,
                stiffness: Some(1e6),
                damping: Some(800.0),
                ..Default::default()
            },
            SupportInput {
                node: 9,
                kxx: Some(Coefficient::Number(1.5e6)),
                kyy: Some(Coefficient::Number(2e6)),
                cxx: Some(Coefficient::Number(900.0)),
                ..Default::default()
            },
        ],
        reduction: None,
    })
}

pub fn lin(a: f64, b: f64, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
        .collect()
}

/// Modes 1, 2 stiffen with the supports then saturate at the pinned-pinned bending modes;
/// 3 and 4 go from free-free to pinned.
pub fn mode_frequency(m: usize, k: f64) -> f64 {
    match m {
        0 => 1.0 / (1.0 / (2.0 * k / 54.5) + 1.0 / 144f64.powi(2)).sqrt(),
        1 => 1.0 / (1.0 / (0.1878 * k) + 1.0 / 1140f64.powi(2)).sqrt(),
        2 => (520f64.powi(2) + (2400f64.powi(2) - 520f64.powi(2)) * k / (k + 3e7)).sqrt(),
        _ => (1500f64.powi(2) + (4400f64.powi(2) - 1500f64.powi(2)) * k / (k + 8e7)).sqrt(),
    }
}

pub fn map() -> CriticalSpeedMapResponse {
    let stiffness: Vec<f64> = (0..31)
        .map(|i| 10f64.powf(5.0 + 5.0 * i as f64 / 30.0))
        .collect();
    let frequencies = (0..4)
        .map(|m| stiffness.iter().map(|&k| mode_frequency(m, k)).collect())
        .collect();
    let mut intersections = vec![];
    for (support, node, coefficient, k) in
        [(0, 1, "kxx", 1e6), (1, 9, "kxx", 1.5e6), (1, 9, "kyy", 2e6)]
    {
        for m in 0..4 {
            intersections.push(MapIntersection {
                support,
                node,
                coefficient: coefficient.into(),
                mode: m + 1,
                stiffness: k,
                frequency: mode_frequency(m, k),
            });
        }
    }
    CriticalSpeedMapResponse {
        output_unit: Default::default(),
        stiffness,
        frequencies,
        intersections,
        warnings: vec![],
    }
}

/// Gravity sag of the sample rotor: statics for the reactions and moment, M / EI integrated
/// twice for the deflection, the supports' springs at the bearings.
pub fn statics() -> StaticResponse {
    let segs = [(0.1, 0.04), (1.3, 0.05), (0.1, 0.04)];
    let elems = [1, 8, 1];
    let (xa, xb, ka, kb) = (0.1, 1.4, 1e6, 2e6);
    let dia = |x: f64| -> f64 { if (0.1..=1.4).contains(&x) { 0.05 } else { 0.04 } };
    let area = |x: f64| std::f64::consts::PI * dia(x).powi(2) / 4.0;
    let ei = |x: f64| E * std::f64::consts::PI * dia(x).powi(4) / 64.0;
    let n = 3000;
    let xs = lin(0.0, 1.5, n + 1);
    let dx = 1.5 / n as f64;
    // Loads: the shaft's weight per length and the disk at 0.75 m.
    let w = |x: f64| RHO * area(x) * G;
    let shaft: f64 = xs.windows(2).map(|p| w(0.5 * (p[0] + p[1])) * dx).sum();
    let disk = 32.6 * G;
    let weight = shaft + disk;
    let moment_a: f64 = xs
        .windows(2)
        .map(|p| w(0.5 * (p[0] + p[1])) * dx * (0.5 * (p[0] + p[1]) - xa))
        .sum::<f64>()
        + disk * (0.75 - xa);
    let rb = moment_a / (xb - xa);
    let ra = weight - rb;
    // Sagging moment (positive) at x from the forces left of it.
    let sag = |x: f64| {
        let mut m = 0.0;
        let steps = 600;
        for i in 0..steps {
            let u = x * (i as f64 + 0.5) / steps as f64;
            m -= w(u) * x / steps as f64 * (x - u);
        }
        if x > 0.75 {
            m -= disk * (x - 0.75);
        }
        if x > xa {
            m += ra * (x - xa);
        }
        if x > xb {
            m += rb * (x - xb);
        }
        m
    };
    let shear = |x: f64| {
        let left: f64 = (0..600)
            .map(|i| w(x * (i as f64 + 0.5) / 600.0) * x / 600.0)
            .sum::<f64>()
            + if x > 0.75 { disk } else { 0.0 };
        let up = if x > xa { ra } else { 0.0 } + if x > xb { rb } else { 0.0 };
        -(up - left)
    };
    // y'' = M / EI, y up; two integrations, then a linear part fits the springs.
    let mut slope = vec![0.0; n + 1];
    let mut y = vec![0.0; n + 1];
    for i in 1..=n {
        let xm = 0.5 * (xs[i - 1] + xs[i]);
        slope[i] = slope[i - 1] + sag(xm) / ei(xm) * dx;
        y[i] = y[i - 1] + 0.5 * (slope[i - 1] + slope[i]) * dx;
    }
    let at = |x: f64| y[(x / dx).round() as usize];
    let (ya, yb) = (-ra / ka, -rb / kb);
    let b = ((yb - at(xb)) - (ya - at(xa))) / (xb - xa);
    let a = ya - at(xa) - b * xa;
    let defl = |x: f64| at(x) + a + b * x;
    let mut positions = vec![0.0];
    let mut x0 = 0.0;
    for ((l, _), e) in segs.iter().zip(elems) {
        for k in 1..=e {
            positions.push(x0 + l * k as f64 / e as f64);
        }
        x0 += l;
    }
    let nodes = positions
        .iter()
        .enumerate()
        .map(|(node, &p)| NodeDeflection {
            node,
            position: p,
            deflection: defl(p),
            deflection_x: 0.0,
            slope: (defl(p + 1e-6) - defl(p - 1e-6)) / 2e-6,
            slope_x: 0.0,
        })
        .collect();
    let mut stations = vec![];
    for (e, p) in positions.windows(2).enumerate() {
        for x in [p[0] + 1e-9, p[1] - 1e-9] {
            stations.push(ShaftStation {
                element: e,
                position: x,
                shear: shear(x),
                bending_moment: -sag(x),
                deflection: defl(x),
                deflection_x: 0.0,
            });
        }
    }
    let (mut mm, mut ms) = (&stations[0], &stations[0]);
    for st in &stations {
        if st.bending_moment.abs() > mm.bending_moment.abs() {
            mm = st;
        }
        if st.shear.abs() > ms.shear.abs() {
            ms = st;
        }
    }
    let (max_moment, max_moment_position) = (mm.bending_moment, mm.position);
    let (max_shear, max_shear_position, max_shear_element) = (ms.shear, ms.position, ms.element);
    let md = stations
        .iter()
        .max_by(|a, b| a.deflection.abs().total_cmp(&b.deflection.abs()))
        .unwrap();
    let (max_deflection, max_deflection_position, max_deflection_y) =
        (md.deflection.abs(), md.position, md.deflection);
    StaticResponse {
        diagram: stations.clone(),
        max_moment,
        max_moment_position,
        max_shear,
        max_shear_position,
        max_shear_element,
        max_deflection,
        max_deflection_position,
        max_deflection_y,
        gravity: G,
        supports_model: StaticSupports::Elastic,
        supports: vec![
            SupportReaction {
                support: 0,
                node: 1,
                reaction: ra,
                reaction_x: 0.0,
            },
            SupportReaction {
                support: 1,
                node: 9,
                reaction: rb,
                reaction_x: 0.0,
            },
        ],
        nodes,
        stations,
        weight,
        warnings: vec![],
    }
}

pub fn speeds() -> Vec<f64> {
    lin(0.0, 375.0, 121)
}

pub fn campbell_data() -> CampbellResponse {
    let s = speeds();
    let branch = |mode, whirl, f: &dyn Fn(f64) -> f64, d: &dyn Fn(f64) -> f64| Branch {
        mode,
        whirl,
        frequency: s.iter().map(|&w| Some(f(w))).collect(),
        decay_rate: s.iter().map(|&w| Some(d(w))).collect(),
        log_decrement: s
            .iter()
            .map(|&w| Some(-2.0 * std::f64::consts::PI * d(w) / f(w).abs()))
            .collect(),
        damping_ratio: s.iter().map(|&w| Some(-d(w) / d(w).hypot(f(w)))).collect(),
        whirl_ratio: s
            .iter()
            .map(|&w| Some(if f(w) >= 0.0 { 1.0 } else { -1.0 }))
            .collect(),
    };
    let critical = 122.4 / 0.99;
    let sigma = -2.0 + 0.00568 * critical;
    CampbellResponse {
        nondimensional: false,
        output_unit: Default::default(),
        motion: Default::default(),
        interference: None,
        branches: vec![
            branch(1, Whirl::Forward, &|w| 122.4 + 0.01 * w, &|w| {
                -2.0 + 0.00568 * w
            }),
            branch(1, Whirl::Backward, &|w| -(122.4 - 0.01 * w), &|w| {
                -2.1 - 0.002 * w
            }),
            branch(2, Whirl::Forward, &|w| 480.0 + 0.25 * w, &|w| {
                -9.0 + 0.004 * w
            }),
            branch(2, Whirl::Backward, &|w| -(480.0 - 0.25 * w), &|w| {
                -9.2 - 0.003 * w
            }),
        ],
        speeds: s,
        critical_speeds: vec![critical],
        criticals: vec![CriticalSpeed {
            speed: critical,
            whirl: Whirl::Forward,
            mode: 1,
            branch: 0,
            decay_rate: sigma,
            log_decrement: Some(-2.0 * std::f64::consts::PI * sigma / critical),
            damping_ratio: -sigma / sigma.hypot(critical),
            whirl_ratio: 1.0,
            critically_damped: false,
        }],
        overdamped: vec![],
        ambiguities: vec![],
        threshold: Some(2.0 / 0.00568),
        reduction: None,
        warnings: vec![],
    }
}

pub fn peak(speed: f64, amplitude: f64, af: f64) -> ResponsePeak {
    let sm = 100.0 * (180.0 - speed) / 180.0;
    let req = (17.0 * (1.0 - 1.0 / (af - 1.5))).min(16.0);
    ResponsePeak {
        speed,
        amplitude,
        amplitude_peak_to_peak: 2.0 * amplitude,
        amplification_factor: Some(af),
        critically_damped: Some(af < 2.5),
        one_sided: false,
        half_power: Some([speed * (1.0 - 0.5 / af), speed * (1.0 + 0.5 / af)]),
        separation_margin: Some(sm),
        required_margin: Some(req),
        passes: Some(sm >= req),
        refined: true,
    }
}

pub fn unbalance_data() -> UnbalanceResponseResponse {
    let s = speeds();
    let (wn, zeta, u, m) = (123.6, 0.06, 1.208e-4, 44.0);
    let node = |node, share: f64| {
        let amplitude: Vec<f64> = s
            .iter()
            .map(|&w| {
                share * u / m * (w * w)
                    / ((wn * wn - w * w).powi(2) + (2.0 * zeta * wn * w).powi(2)).sqrt()
            })
            .collect();
        let phase: Vec<f64> = s
            .iter()
            .map(|&w| -(2.0 * zeta * wn * w).atan2(wn * wn - w * w))
            .collect();
        let top = share * u / m / (2.0 * zeta * (1.0 - zeta * zeta).sqrt());
        NodeUnbalance {
            node,
            x_amplitude: amplitude.clone(),
            y_amplitude: amplitude.clone(),
            major: amplitude.clone(),
            minor: amplitude.clone(),
            x_phase: phase.clone(),
            y_phase: phase.clone(),
            phase,
            amplitude,
            peaks: vec![peak(
                wn / (1.0 - 2.0 * zeta * zeta).sqrt(),
                top,
                1.0 / (2.0 * zeta),
            )],
        }
    };
    let nodes = vec![node(5, 1.0), node(1, 0.31), node(9, 0.27)];
    UnbalanceResponseResponse {
        nondimensional: false,
        output_unit: Default::default(),
        speeds: s,
        nodes,
        reduction: None,
        full_model: Default::default(),
        note: "Synchronous response; hysteretic damping at omega = Omega.".into(),
        warnings: vec![],
    }
}

/// `delta(q) = 0.42 - 4e-8 q - b q^2`, zero at q0 = 8.6e6 N/m.
pub const Q0: f64 = 8.6e6;
pub fn level1_data() -> Level1Response {
    let b = (0.42 - 4e-8 * Q0) / (Q0 * Q0);
    let d = |q: f64| 0.42 - 4e-8 * q - b * q * q;
    let q = lin(0.0, 2e7, 21);
    let qa = 2.2e6;
    Level1Response {
        output_unit: Default::default(),
        speed: 300.0,
        nodes: vec![5],
        weights: vec![1.0],
        log_decrement: q.iter().map(|&q| Some(d(q))).collect(),
        frequency: q.iter().map(|&q| Some(123.0 + 1e-7 * q)).collect(),
        cross_coupling: q,
        log_decrement_0: Some(d(0.0)),
        frequency_0: Some(123.0),
        q0: Some(Q0),
        qa: Some(qa),
        log_decrement_at_qa: Some(d(qa)),
        ratio: Some(Q0 / qa),
        passes: Some(true),
        level2_required: Some(false),
        level2_reasons: vec![],
        rigid_critical_speed: None,
        critical_speed_ratio: None,
        region: None,
        level2: None,
        reduction: None,
        max_residual: None,
        model: "hysteretic".into(),
        warnings: vec![],
    }
}

pub fn frequency_data() -> FrequencyResponseResponse {
    let f = lin(5.0, 1000.0, 400);
    let h = |w: f64| {
        let m1 = num_complex::Complex64::new(6.657e5 - 44.0 * w * w, 2.0 * 0.06 * 123.0 * 44.0 * w);
        let m2 = num_complex::Complex64::new(5e6 - 21.0 * w * w, 2.0 * 0.03 * 488.0 * 21.0 * w);
        1.0 / m1 + 0.4 / m2
    };
    let amp: Vec<f64> = f.iter().map(|&w| h(w).norm()).collect();
    let phase: Vec<f64> = f.iter().map(|&w| h(w).arg()).collect();
    FrequencyResponseResponse {
        output_unit: Default::default(),
        reduction: None,
        full_model: Default::default(),
        speed: 300.0,
        input_node: 5,
        output_node: 5,
        x_amplitude: amp.clone(),
        x_phase: phase.clone(),
        y_amplitude: vec![0.0; f.len()],
        y_phase: vec![0.0; f.len()],
        forward: amp.iter().map(|a| a / 2.0).collect(),
        backward: amp.iter().map(|a| a / 2.0).collect(),
        elements: vec![],
        frequencies: f,
        amplitude: amp,
        phase,
        model: "hysteretic".into(),
        warnings: vec![],
    }
}

pub fn check(
    check: &str,
    model: &str,
    value: &str,
    requirement: &str,
    passes: bool,
) -> ReportCheck {
    ReportCheck {
        check: check.into(),
        model: model.into(),
        value: value.into(),
        requirement: requirement.into(),
        passes,
    }
}

pub fn margins(
    model: &str,
    crit: f64,
    threshold: Option<f64>,
    logdec: f64,
    q0: f64,
    af: f64,
) -> ModelMargins {
    ModelMargins {
        model: model.into(),
        critical_speeds: vec![crit],
        threshold,
        log_decrement: Some(logdec),
        q0: Some(q0),
        peaks: vec![peak(crit, 2.3e-5, af)],
    }
}

pub fn report() -> ReportResponse {
    let l = level1_data();
    ReportResponse {
        torsion: None,
        rotor: rotor(),
        operating_range: OperatingRange {
            min: 180.0,
            max: 300.0,
            unit: None,
        },
        critical_speed_map: map(),
        static_deflection: statics(),
        campbell: campbell_data(),
        unbalance: unbalance_data(),
        unbalance_cases: vec![],
        bearing_sets: vec![],
        vibration_limit: 25.4e-6,
        provenance: None,
        models: vec![
            margins("hysteretic", 123.6, Some(352.1), 0.33, Q0, 8.33),
            margins("equivalent", 123.4, None, 0.36, 9.4e6, 7.6),
            margins("nonviscous", 123.5, Some(365.0), 0.34, 8.8e6, 8.1),
            margins("viscous", 123.9, None, 0.05, 1.1e6, 25.0),
        ],
        checks: vec![
            check(
                "separation margin, 1st critical (1180 rpm)",
                "hysteretic",
                "31.3%",
                "≥ 14.5% (AF 8.33)",
                true,
            ),
            check(
                "Level I: log decrement at q_A",
                "hysteretic",
                &format!("{:.3}", l.log_decrement_at_qa.unwrap()),
                "≥ 0.1",
                true,
            ),
            check("Level I: q0 / q_A", "hysteretic", "3.91", "≥ 2", true),
            check(
                "onset of instability",
                "hysteretic",
                "352.1 rad/s",
                "> 300 rad/s (MCS)",
                true,
            ),
            check("log decrement at MCS", "viscous", "0.050", "≥ 0.1", false),
        ],
        level1: l,
        unbalances: vec![SteadyUnbalanceInput {
            node: 5,
            amount: 1.208e-4,
            phase: 0.0,
        }],
        warnings: vec![],
    }
}

// --- SVG reading -------------------------------------------------------------------------

/// Attributes of every `<tag ...>` element.
pub fn elements(svg: &str, tag: &str) -> Vec<BTreeMap<String, String>> {
    let open = format!("<{tag} ");
    let mut out = vec![];
    for part in svg.split(&open).skip(1) {
        let head = &part[..part.find('>').unwrap()];
        let mut attrs = BTreeMap::new();
        for kv in head.split("\" ") {
            if let Some((k, v)) = kv.trim().split_once("=\"") {
                attrs.insert(k.to_string(), v.trim_end_matches(['"', '/']).to_string());
            }
        }
        out.push(attrs);
    }
    out
}

pub fn f(a: &BTreeMap<String, String>, k: &str) -> f64 {
    a[k].parse().unwrap()
}

pub fn points(a: &BTreeMap<String, String>) -> Vec<(f64, f64)> {
    a["points"]
        .split_whitespace()
        .map(|p| {
            let (x, y) = p.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

/// The framed plotting areas, `[x0, y0, x1, y1]`, top to bottom.
pub fn frames(svg: &str) -> Vec<[f64; 4]> {
    let mut r: Vec<[f64; 4]> = elements(svg, "rect")
        .iter()
        .filter(|a| a.get("stroke").map(String::as_str) == Some("#505050") && a["fill"] == "none")
        .map(|a| {
            let (x, y) = (f(a, "x"), f(a, "y"));
            [x, y, x + f(a, "width"), y + f(a, "height")]
        })
        .collect();
    r.sort_by(|a, b| a[1].total_cmp(&b[1]));
    r
}

pub fn inside(r: &[f64; 4], (x, y): (f64, f64)) -> bool {
    r[0] - 0.5 <= x && x <= r[2] + 0.5 && r[1] - 0.5 <= y && y <= r[3] + 0.5
}

/// No `NaN` and no `inf` standing as a number.
pub fn finite_text(s: &str) {
    assert!(!s.contains("NaN"), "NaN in output");
    for (i, _) in s.match_indices("inf") {
        let before = s[..i].chars().last().unwrap_or(' ');
        assert!(
            before.is_alphabetic(),
            "inf in output: {}",
            &s[i.saturating_sub(20)..(i + 20).min(s.len())]
        );
    }
}

/// A compressor-like rotor: hollow segments, many elements, three disks, a table support.
pub fn dense_rotor() -> RotorInput {
    let RotorInput::Beam(mut b) = rotor() else {
        unreachable!()
    };
    b.shaft = [
        (0.12, 0.06, 0.0, 3),
        (0.5, 0.09, 0.04, 12),
        (0.7, 0.11, 0.05, 16),
        (0.3, 0.07, 0.0, 5),
    ]
    .into_iter()
    .map(|(length, outer_diameter, inner_diameter, e)| SegmentInput {
        length,
        outer_diameter,
        inner_diameter,
        material: "steel".into(),
        elements: Some(e),
        ..Default::default()
    })
    .collect();
    b.disks = vec![
        DiskInput {
            node: 10,
            mass: 48.0,
            polar_inertia: 0.9,
            transverse_inertia: 0.48,
        },
        DiskInput {
            node: 22,
            mass: 61.0,
            polar_inertia: 1.2,
            transverse_inertia: 0.63,
        },
        DiskInput {
            node: 30,
            mass: 12.0,
            polar_inertia: 0.0,
            transverse_inertia: 0.0,
        },
    ];
    b.supports = vec![
        SupportInput {
            node: 2,
            stiffness: Some(2e8),
            ..Default::default()
        },
        SupportInput {
            node: 33,
            kxx: Some(Coefficient::Table(vec![1e8, 2e8, 3e8])),
            speeds: Some(vec![0.0, 500.0, 1000.0]),
            ..Default::default()
        },
        SupportInput {
            node: 33,
            stiffness: Some(5e6),
            ..Default::default()
        },
    ];
    RotorInput::Beam(b)
}
