//! `POST /v1/convert/ross` (issue 29): five machines built in ROSS 2.3.0 and saved by its own
//! `Rotor.save` (`tests/data/ross/convert.py`), each posted to the endpoint through the app
//! without a socket; Whirl's modal analysis (`/v1/modal`) and unbalance response
//! (`/v1/unbalance-response`) of the converted rotor against ROSS's on the rotor it loads back
//! from the same file: every lateral pole within 1e-6 of the largest |s| at its speed, every
//! response value within 1e-6 of the largest |X| of its node and direction. Then the refusals:
//! malformed TOML (its line named), elements that cannot be converted (their tables named), a
//! body not declared as TOML, too many elements, too large a body.

use http_body_util::BodyExt;
use serde_json::{Value, json};
use tower::ServiceExt;
use whirl::service::{Config, app};

const TOLERANCE: f64 = 1e-6;

fn dir() -> String {
    format!("{}/tests/data/ross/convert", env!("CARGO_MANIFEST_DIR"))
}

fn toml(name: &str) -> String {
    std::fs::read_to_string(format!("{}/{name}.toml", dir())).unwrap()
}

fn reference(name: &str) -> Value {
    serde_json::from_str(&std::fs::read_to_string(format!("{}/{name}.json", dir())).unwrap())
        .unwrap()
}

/// Sends a body of `content_type` to the in-process app: the status and the JSON answer.
async fn send_with(
    config: Config,
    uri: &str,
    content_type: Option<&str>,
    body: Vec<u8>,
) -> (u16, Value) {
    let mut req = axum::http::Request::builder().method("POST").uri(uri);
    if let Some(ct) = content_type {
        req = req.header("content-type", ct);
    }
    let resp = app(config)
        .oneshot(req.body(axum::body::Body::from(body)).unwrap())
        .await
        .unwrap();
    let status = resp.status().as_u16();
    let bytes = resp.into_body().collect().await.unwrap().to_bytes();
    (
        status,
        serde_json::from_slice(&bytes).unwrap_or(Value::Null),
    )
}

async fn send(uri: &str, content_type: Option<&str>, body: Vec<u8>) -> (u16, Value) {
    send_with(Config::default(), uri, content_type, body).await
}

async fn convert(text: &str) -> (u16, Value) {
    send(
        "/v1/convert/ross",
        Some("application/toml"),
        text.as_bytes().to_vec(),
    )
    .await
}

async fn post(uri: &str, body: Value) -> Value {
    let (status, v) = send(uri, Some("application/json"), body.to_string().into_bytes()).await;
    assert_eq!(status, 200, "{uri}: {v}");
    v
}

#[derive(Clone, Copy, Debug)]
struct C(f64, f64);

impl C {
    fn of(v: &Value) -> C {
        C(v[0].as_f64().unwrap(), v[1].as_f64().unwrap())
    }
    fn polar(r: f64, phase: f64) -> C {
        C(r * phase.cos(), r * phase.sin())
    }
    fn norm(self) -> f64 {
        self.0.hypot(self.1)
    }
    fn minus(self, o: C) -> C {
        C(self.0 - o.0, self.1 - o.1)
    }
}

/// Largest distance from each value of one set to the nearest of the other, both ways.
fn set_distance(a: &[C], b: &[C]) -> f64 {
    let one_way = |a: &[C], b: &[C]| {
        a.iter()
            .map(|s| {
                b.iter()
                    .map(|t| s.minus(*t).norm())
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max)
    };
    one_way(a, b).max(one_way(b, a))
}

/// Converts `name`'s file, checks the warnings hold each of `warnings`, and returns the rotor.
async fn converted(name: &str, warnings: &[&str]) -> Value {
    let (status, v) = convert(&toml(name)).await;
    assert_eq!(status, 200, "{name}: {v}");
    let said: Vec<&str> = v["warnings"]
        .as_array()
        .unwrap()
        .iter()
        .map(|w| w.as_str().unwrap())
        .collect();
    for w in warnings {
        assert!(
            said.iter().any(|s| s.contains(w)),
            "{name}: no warning with `{w}` in {said:#?}"
        );
    }
    v["rotor"].clone()
}

/// Whirl's poles of the converted rotor at each reference speed against ROSS's lateral
/// eigenvalues. ROSS's real system has each of Whirl's poles and its conjugate.
async fn poles_match(name: &str, rotor: &Value, d: &Value) {
    let mut worst: f64 = 0.0;
    for case in d["poles"].as_array().unwrap() {
        let speed = case["speed"].as_f64().unwrap();
        let want: Vec<C> = case["eigenvalues"]
            .as_array()
            .unwrap()
            .iter()
            .map(C::of)
            .collect();
        let v = post(
            "/v1/modal",
            json!({"rotor": rotor, "damping": {"model": "viscous"}, "speed": speed}),
        )
        .await;
        assert_eq!(v["missing_poles"], 0, "{name} at {speed}");
        // Anisotropic rotors are solved in (r, conj r): as many states as ROSS's real system,
        // each complex pair reported once. Isotropic ones in r alone: half as many, and each
        // pole stands for itself and its conjugate in ROSS's system (a real pole twice).
        let doubled = v["states"].as_u64() == Some(want.len() as u64);
        let mut got = vec![];
        for p in v["poles"].as_array().unwrap() {
            let s = C(
                p["decay_rate"].as_f64().unwrap(),
                p["frequency"].as_f64().unwrap(),
            );
            got.push(s);
            if !doubled || s.1.abs() > 1e-9 * s.norm() {
                got.push(C(s.0, -s.1));
            }
        }
        assert_eq!(got.len(), want.len(), "{name} at {speed}: pole count");
        let scale = want.iter().map(|s| s.norm()).fold(0.0, f64::max);
        let e = set_distance(&want, &got) / scale;
        worst = worst.max(e);
        assert!(
            e <= TOLERANCE,
            "{name} at {speed} rad/s: poles {e:.2e} of the largest |s| ({scale:.4e}) from ROSS's"
        );
    }
    println!("{name}: poles within {worst:.2e} of ROSS's largest |s|");
}

/// Whirl's unbalance response of the converted rotor against ROSS's X and Y.
async fn unbalance_match(name: &str, rotor: &Value, d: &Value) {
    let u = &d["unbalance_response"];
    let nodes: Vec<Value> = u["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n["node"].clone())
        .collect();
    let v = post(
        "/v1/unbalance-response",
        json!({
            "rotor": rotor,
            "damping": {"model": "viscous"},
            "speeds": u["speeds"],
            "unbalances": u["unbalances"],
            "nodes": nodes,
            "modal_reduction": false,
        }),
    )
    .await;
    let speeds = u["speeds"].as_array().unwrap();
    let mut worst: f64 = 0.0;
    for reference in u["nodes"].as_array().unwrap() {
        let node = &reference["node"];
        let answer = v["nodes"]
            .as_array()
            .unwrap()
            .iter()
            .find(|n| n["node"] == *node)
            .unwrap_or_else(|| panic!("{name}: node {node} not answered"));
        for axis in ["x", "y"] {
            let want: Vec<C> = reference[axis]
                .as_array()
                .unwrap()
                .iter()
                .map(C::of)
                .collect();
            let peak = want.iter().map(|z| z.norm()).fold(0.0, f64::max);
            for (i, w) in want.iter().enumerate() {
                let got = C::polar(
                    answer[format!("{axis}_amplitude")][i].as_f64().unwrap(),
                    answer[format!("{axis}_phase")][i].as_f64().unwrap(),
                );
                let e = got.minus(*w).norm() / peak;
                worst = worst.max(e);
                assert!(
                    e <= TOLERANCE,
                    "{name} node {node} {axis} at {} rad/s: {got:?} against ROSS's {w:?} \
                     ({e:.2e} of the peak {peak:.3e})",
                    speeds[i]
                );
            }
        }
    }
    println!("{name}: unbalance response within {worst:.2e} of ROSS's peak");
}

/// Converts `name`'s file and checks the rotor against ROSS's own results (tables read with
/// ROSS's interpolation, as the converter writes them).
async fn machine(name: &str, warnings: &[&str]) -> Value {
    let rotor = converted(name, warnings).await;
    let d = reference(name);
    poles_match(name, &rotor, &d).await;
    unbalance_match(name, &rotor, &d).await;
    rotor
}

/// The converted rotor with its tables read linearly instead (`interpolation` removed) against
/// ROSS's rotor with its tables frozen at that linear interpolation (convert.py's `linear`):
/// the two ways of reading a table each reproduce ROSS's.
async fn linear_too(name: &str, rotor: &Value) {
    let mut linear = rotor.clone();
    let mut tables = 0;
    for key in ["supports", "seals"] {
        for s in linear[key].as_array_mut().into_iter().flatten() {
            if s.as_object_mut().unwrap().remove("interpolation").is_some() {
                tables += 1;
            }
        }
    }
    assert!(
        tables > 0,
        "{name}: no table read with ROSS's interpolation"
    );
    let d = &reference(name)["linear"];
    let label = format!("{name} (linear tables)");
    poles_match(&label, &linear, d).await;
    unbalance_match(&label, &linear, d).await;
}

fn count(rotor: &Value, key: &str) -> usize {
    rotor[key].as_array().map_or(0, Vec::len)
}

#[tokio::test]
async fn rosss_compressor_example_with_its_sleeves_and_tables() {
    let rotor = machine("compressor_example", &[]).await;
    linear_too("compressor_example", &rotor).await;
    // 91 shaft elements on 55 nodes: 36 sleeves; 7 disks; 2 bearings, 12 seals.
    assert_eq!(count(&rotor, "sleeves"), 36);
    let elements: i64 = rotor["shaft"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["elements"].as_i64().unwrap_or(1))
        .sum();
    assert_eq!(elements, 55);
    assert_eq!(count(&rotor, "disks"), 7);
    assert_eq!(count(&rotor, "supports"), 2);
    assert_eq!(count(&rotor, "seals"), 12);
    for s in rotor["seals"].as_array().unwrap() {
        assert!(s["speeds"].is_array(), "{s}");
        assert_eq!(s["interpolation"], "ross", "{s}");
    }
    // The sleeves' material: E = G_s = 1 psi, so Poisson = -0.5.
    let materials = rotor["materials"].as_object().unwrap();
    assert_eq!(materials.len(), 2, "{materials:?}");
    assert_eq!(materials["shaft_mat_2"]["poisson_ratio"], -0.5);
}

#[tokio::test]
async fn a_rotor_on_pedestals_with_point_masses_on_and_off_the_shaft() {
    let rotor = machine(
        "pedestals",
        &[
            "PointMass_Point Mass 2: its mass is added to node 3's translations",
            "mx = 18 and my = 20 differ",
        ],
    )
    .await;
    // ROSS's node numbers: the pedestals are nodes 11 and 12, the shaft's 0 to 10.
    let links: Vec<(i64, i64)> = rotor["supports"]
        .as_array()
        .unwrap()
        .iter()
        .filter_map(|s| Some((s["node"].as_i64()?, s["n_link"].as_i64()?)))
        .collect();
    assert_eq!(links, vec![(0, 11), (10, 12)]);
    let masses: Vec<(i64, f64)> = rotor["point_masses"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| (p["node"].as_i64().unwrap(), p["mass"].as_f64().unwrap()))
        .collect();
    assert_eq!(masses, vec![(11, 15.0), (12, 18.0), (3, 4.0)]);
    // The shaft: one segment of 10 equal elements.
    assert_eq!(rotor["shaft"].as_array().unwrap().len(), 1);
    assert_eq!(rotor["shaft"][0]["elements"], 10);
}

#[tokio::test]
async fn a_tapered_rotor() {
    let rotor = machine("tapered", &[]).await;
    let shaft = rotor["shaft"].as_array().unwrap();
    assert_eq!(shaft.len(), 8);
    for s in shaft {
        assert!(s["outer_diameter_right"].is_number(), "{s}");
        assert!(s["inner_diameter_right"].is_number(), "{s}");
        assert!(s.get("shear_factor").is_none(), "{s}");
    }
}

#[tokio::test]
async fn a_rotor_under_axial_force_and_torque_with_proportional_damping() {
    let rotor = machine("axial_rayleigh", &["`frame: \"nonrotating\"`"]).await;
    let shaft = rotor["shaft"].as_array().unwrap();
    for s in shaft {
        assert_eq!(s["axial_force"], -1.5e4, "{s}");
        // The element with the torque has no beta (see convert.py).
        let beta = if s.get("torque").is_some() { 0.0 } else { 2e-5 };
        assert_eq!(
            s["rayleigh_damping"],
            json!({"alpha": 1.5, "beta": beta, "frame": "nonrotating"})
        );
    }
    let torque: Vec<&Value> = shaft.iter().filter(|s| s.get("torque").is_some()).collect();
    assert_eq!(torque.len(), 1);
    assert_eq!(torque[0]["torque"], 1e3);
}

#[tokio::test]
async fn a_bearing_table_of_70_speeds_and_a_tabulated_seal() {
    let rotor = machine("table70", &[]).await;
    linear_too("table70", &rotor).await;
    for s in rotor["supports"].as_array().unwrap() {
        assert_eq!(s["speeds"].as_array().unwrap().len(), 70);
        assert_eq!(s["interpolation"], "ross", "{s}");
    }
    assert_eq!(rotor["seals"][0]["speeds"], json!([300.0, 1500.0, 3000.0]));
}

/// The paths of a 422's errors.
fn paths(v: &Value) -> Vec<String> {
    v["errors"]
        .as_array()
        .unwrap_or(&vec![])
        .iter()
        .map(|e| e["path"].as_str().unwrap().to_string())
        .collect()
}

fn message(v: &Value, path: &str) -> String {
    v["errors"]
        .as_array()
        .unwrap()
        .iter()
        .find(|e| e["path"] == path)
        .unwrap_or_else(|| panic!("no error at {path}: {v}"))["message"]
        .as_str()
        .unwrap()
        .to_string()
}

#[tokio::test]
async fn malformed_toml_is_a_400_naming_its_line() {
    let mut text = toml("tapered");
    let lines = text.lines().count();
    text.push_str("[\"BearingElement_x\"]\nn = = 3\n");
    let (status, v) = convert(&text).await;
    assert_eq!(status, 400, "{v}");
    assert!(
        v["type"]
            .as_str()
            .unwrap()
            .ends_with("/problems/malformed-toml")
    );
    assert_eq!(v["title"], "Malformed TOML");
    let detail = v["detail"].as_str().unwrap();
    assert!(detail.contains(&format!("line {}", lines + 2)), "{detail}");
    // A table given twice is not TOML either; nor is text that is not UTF-8.
    let twice = format!(
        "{}\n{}",
        toml("tapered"),
        "[\"DiskElement_Disk 0\"]\nn = 4\n"
    );
    let (status, v) = convert(&twice).await;
    assert_eq!(status, 400, "{v}");
    let (status, v) = send(
        "/v1/convert/ross",
        Some("application/toml"),
        b"a = \"\xff\"\n".to_vec(),
    )
    .await;
    assert_eq!(status, 400, "{v}");
    assert!(v["detail"].as_str().unwrap().contains("UTF-8"), "{v}");
}

#[tokio::test]
async fn elements_that_cannot_be_converted_are_named_by_their_tables() {
    let base = toml("pedestals");
    let with = |extra: &str| format!("{base}\n{extra}");
    // An element class Whirl cannot hold, and one ROSS does not have.
    let (status, v) = convert(&with(
        "[MagneticBearingElement_3]\nn = 3\ng0 = 0.001\ni0 = 1.0\nag = 1e-4\nnw = 200\n\
         kxx = [1e6]\ncxx = [1e2]\n\n[FancyElement_1]\nn = 2\n",
    ))
    .await;
    assert_eq!(status, 422, "{v}");
    let p = paths(&v);
    assert!(p.contains(&"MagneticBearingElement_3".to_string()), "{p:?}");
    assert!(p.contains(&"FancyElement_1".to_string()), "{p:?}");
    assert!(message(&v, "MagneticBearingElement_3").contains("controller"));
    // A shaft element option that is not a boolean, and a bad value, each with its line.
    let lines: Vec<&str> = base.lines().collect();
    let at = lines
        .iter()
        .position(|l| l.starts_with("rotary_inertia"))
        .unwrap();
    let mut edited: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    edited[at] = "rotary_inertia = 3".into();
    let l_at = lines.iter().position(|l| l.starts_with("L = ")).unwrap();
    edited[l_at] = "L = -0.15".into();
    let (status, v) = convert(&edited.join("\n")).await;
    assert_eq!(status, 422, "{v}");
    let table = "ShaftElement_Shaft Element 0";
    let m = message(&v, &format!("{table}.rotary_inertia"));
    assert!(m.contains(&format!("(line {})", at + 1)), "{m}");
    let m = message(&v, &format!("{table}.L"));
    assert!(
        m.contains("must be > 0") && m.contains(&format!("(line {})", l_at + 1)),
        "{m}"
    );
    // A point mass off the shaft leaving a gap in ROSS's numbering.
    let gap = base.replace("n = 12\nmx = 18.0", "n = 13\nmx = 18.0");
    assert_ne!(gap, base);
    let (status, v) = convert(&gap).await;
    assert_eq!(status, 422, "{v}");
    assert!(
        paths(&v)
            .iter()
            .any(|p| p.starts_with("PointMass_") && p.ends_with(".n")),
        "{v}"
    );
}

/// A train of three shafts joined by two ROSS `CouplingElement`s: each a coupling segment on its
/// node (the second's `Id` by ROSS's default, half its `Ip`), ROSS's poles and unbalance
/// response on all three shafts; an anisotropic coupling, and one sharing its node with a shaft
/// element, are refused naming the table.
#[tokio::test]
async fn a_train_of_three_shafts_joined_by_couplings() {
    let rotor = machine("train", &["CouplingElement's dampers"]).await;
    let shaft = rotor["shaft"].as_array().unwrap();
    let couplings: Vec<&Value> = shaft
        .iter()
        .filter(|s| s.get("coupling").is_some())
        .collect();
    assert_eq!(couplings.len(), 2, "{shaft:?}");
    assert_eq!(
        couplings[1]["coupling"]["transverse_inertia"],
        json!([0.01, 0.01])
    );
    let base = toml("train");
    let table = "CouplingElement_Coupling 6";
    let start = base.find(&format!("[\"{table}\"]")).unwrap();
    let kt_y = start + base[start..].find("kt_y = ").unwrap();
    let anisotropic = format!(
        "{}kt_y = 2.5e7{}",
        &base[..kt_y],
        &base[kt_y + "kt_y = 20000000.0".len()..]
    );
    let (status, v) = convert(&anisotropic).await;
    assert_eq!(status, 422, "{v}");
    assert!(
        message(&v, &format!("{table}.kt_y")).contains("isotropic"),
        "{v}"
    );
    let n = start + base[start..].find("\nn = 6\n").unwrap();
    let shared = format!("{}\nn = 5\n{}", &base[..n], &base[n + "\nn = 6\n".len()..]);
    let (status, v) = convert(&shared).await;
    assert_eq!(status, 422, "{v}");
    assert!(paths(&v).contains(&table.to_string()), "{v}");
}

#[tokio::test]
async fn a_body_not_declared_as_toml_is_a_415() {
    for ct in [Some("application/json"), Some("text/plain"), None] {
        let (status, v) = send("/v1/convert/ross", ct, toml("tapered").into_bytes()).await;
        assert_eq!(status, 415, "{ct:?}: {v}");
        assert!(v["detail"].as_str().unwrap().contains("application/toml"));
    }
}

#[tokio::test]
async fn too_many_elements_are_refused_before_anything_is_built() {
    // 600 shaft elements: 1202 degrees of freedom, past the default limit of 1000.
    let mut text = String::from("ross_version = \"2.3.0\"\n");
    for i in 0..600 {
        text.push_str(&format!(
            "[\"ShaftElement_{i}\"]\nL = 0.01\nidl = 0.0\nodl = 0.05\nn = {i}\n\
             [\"ShaftElement_{i}\".material]\nname = \"Steel\"\nrho = 7810.0\nE = 2.11e11\n\
             G_s = 8.12e10\n"
        ));
    }
    let (status, v) = convert(&text).await;
    assert_eq!(status, 422, "{v}");
    let m = message(&v, "ShaftElement");
    assert!(
        m.contains("1202 degrees of freedom") && m.contains("WHIRL_MAX_DOFS"),
        "{m}"
    );
    // More tables than could ever be read: refused from their count.
    let (status, v) = send_with(
        Config {
            max_dofs: 60,
            ..Config::default()
        },
        "/v1/convert/ross",
        Some("application/toml"),
        text.into_bytes(),
    )
    .await;
    assert_eq!(status, 422, "{v}");
    assert!(
        message(&v, "ShaftElement").contains("600 shaft elements"),
        "{v}"
    );
    // And a body past the size limit is a 413 before it is read.
    let (status, v) = send_with(
        Config {
            max_body_bytes: 1024,
            ..Config::default()
        },
        "/v1/convert/ross",
        Some("application/toml"),
        toml("tapered").into_bytes(),
    )
    .await;
    assert_eq!(status, 413, "{v}");
}

/// Bearing classes other than BearingElement are tables of coefficients once built: ROSS saves
/// the coefficients beside the constructor's arguments (here as ROSS 2.3.0 wrote them).
#[tokio::test]
async fn other_bearing_classes_convert_from_their_saved_coefficients() {
    let tapered = toml("tapered").replace("ross_version = \"2.3.0\"", "ross_version = \"2.2.0\"");
    let text = format!(
        "{tapered}\n{}",
        r##"["RollerBearingElement_Roller Bearing 2"]
alpha = 0.5235987755982988
color = "#355d7a"
cxx = [ 3410.2740925075814,]
cxy = [ 0.0,]
cyx = [ 0.0,]
cyy = [ 6959.74304593384,]
czz = [ 0,]
fs = 500.0
kxx = [ 272821927.4006065,]
kxy = [ 0.0,]
kyx = [ 0.0,]
kyy = [ 556779443.6747072,]
kzz = [ 1e5,]
l_rollers = 0.03
mxx = [ 0,]
mxy = [ 0,]
myx = [ 0,]
myy = [ 0,]
mzz = [ 0,]
n = 4
n_rollers = 8
scale_factor = 1
tag = "Roller Bearing 2"
"##
    );
    let (status, v) = convert(&text).await;
    assert_eq!(status, 200, "{v}");
    let roller = v["rotor"]["supports"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["node"] == 4)
        .unwrap()
        .clone();
    // (serde_json's default parser may round the last bit: compare to 1e-15.) Its axial
    // stiffness is kept for the axial analyses.
    let want = json!({"node": 4, "kxx": 272821927.4006065, "kyy": 556779443.6747072,
                      "cxx": 3410.2740925075814, "cyy": 6959.74304593384, "kzz": 1e5});
    assert_eq!(
        roller.as_object().unwrap().len(),
        want.as_object().unwrap().len(),
        "{roller}"
    );
    for (k, w) in want.as_object().unwrap() {
        let (got, w) = (roller[k].as_f64().unwrap(), w.as_f64().unwrap());
        assert!((got - w).abs() <= 1e-15 * w.abs(), "{k}: {got} against {w}");
    }
    let warnings = v["warnings"].to_string();
    assert!(warnings.contains("ROSS 2.2.0"), "{warnings}");
    // Its axial stiffness is carried, not dropped.
    assert!(!warnings.contains("kzz"), "{warnings}");
}
