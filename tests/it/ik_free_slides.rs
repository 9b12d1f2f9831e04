//! 7-joint arms whose six locked joints include slides (a 6R1P, a 5R2P and a 4R3P chain), every
//! joint in turn the free one: the derivation picks a family or the general method, and at
//! random configurations (the free joint's value given) every solution reproduces the pose to
//! 1e-9 by the independent classic-DH model of `ik_general_prismatic`, the original
//! configuration among them.

use crate::common::Rng;
use crate::ik_general_prismatic::{deviation, dh_toml, dist, pose, pri, random_q, rev, size, Row};
use dqsym::ik::{solve, IkMethod, IkOptions, IkSolution};

const PI: f64 = std::f64::consts::PI;

fn six_r_one_p() -> Vec<Row> {
    vec![
        rev(0.15, 0.2, ("pi/4", PI / 4.0)),
        rev(0.3, 0.1, ("pi/3", PI / 3.0)),
        rev(0.05, 0.4, ("pi/5", PI / 5.0)),
        pri(("pi/6", PI / 6.0), 0.07, ("-pi/4", -PI / 4.0)),
        rev(0.2, 0.03, ("2*pi/5", 2.0 * PI / 5.0)),
        rev(0.11, 0.06, ("-pi/3", -PI / 3.0)),
        rev(0.09, 0.02, ("pi/7", PI / 7.0)),
    ]
}

fn five_r_two_p() -> Vec<Row> {
    let mut rows = six_r_one_p();
    rows[5] = pri(("-pi/4", -PI / 4.0), 0.06, ("-pi/3", -PI / 3.0));
    rows
}

fn four_r_three_p() -> Vec<Row> {
    vec![
        rev(0.15, 0.2, ("pi/4", PI / 4.0)),
        pri(("pi/6", PI / 6.0), 0.07, ("-pi/4", -PI / 4.0)),
        rev(0.3, 0.1, ("pi/2", PI / 2.0)),
        pri(("-pi/4", -PI / 4.0), 0.06, ("pi/2", PI / 2.0)),
        rev(0.05, 0.4, ("pi/3", PI / 3.0)),
        pri(("pi/3", PI / 3.0), 0.09, ("pi/6", PI / 6.0)),
        rev(0.2, 0.03, ("-pi/2", -PI / 2.0)),
    ]
}

fn derive_free(name: &str, rows: &[Row], free: Option<&str>) -> Result<IkSolution, String> {
    let text = dh_toml(name, rows);
    let robot = dqsym::parse_robot(&text, name, &dqsym::eval_scalar_text).expect("robot");
    solve(
        &robot,
        &IkOptions {
            free: free.map(str::to_string),
            method: IkMethod::Auto,
        },
    )
    .map_err(|e| e.to_string())
}

/// At `n` random configurations: the free joint's value as the parameter, every unflagged
/// solution (with the free value put back) reproduces the pose to 1e-9, the original among
/// them.
fn round_trips(name: &str, rows: &[Row], sol: &IkSolution, n: usize, seed: u64) {
    let free = sol.free.clone().expect("a free joint");
    let k: usize = free[1..].parse::<usize>().expect("q<k>") - 1;
    let len = size(rows);
    let mut rng = Rng::new(seed);
    for _ in 0..n {
        let q = random_q(rows, &mut rng);
        let t = pose(rows, &q);
        let sols = sol
            .solve_numeric(&t, &[(free.as_str(), q[k])])
            .expect("solve");
        let full = |s: &[f64]| -> Vec<f64> {
            let mut v = s.to_vec();
            v.insert(k, q[k]);
            v
        };
        for s in sols.iter().filter(|s| !s.approximate) {
            let dev = deviation(&t, &pose(rows, &full(&s.q)), len);
            assert!(
                dev <= 1e-9,
                "{name} ({free} free): {:?} misses by {dev}",
                s.q
            );
        }
        assert!(
            sols.iter()
                .any(|s| !s.approximate && dist(rows, &full(&s.q), &q) <= 1e-6),
            "{name} ({free} free): {q:?} not among {sols:?}"
        );
    }
}

/// Without `--free` the derivation picks a free joint (an end joint first); with each joint
/// in turn given as `--free`, every choice that derives round-trips, and the choices that leave
/// six joints of a solvable kind (at least one turn, not two slides three apart) all derive.
#[test]
fn seven_joint_arms_with_slides_round_trip_for_every_free_joint() {
    for (name, rows) in [
        ("6R1P", six_r_one_p()),
        ("5R2P", five_r_two_p()),
        ("4R3P", four_r_three_p()),
    ] {
        let sol = derive_free(name, &rows, None).unwrap_or_else(|e| panic!("{name}: {e}"));
        eprintln!(
            "{name}: {} free, {}",
            sol.free.clone().unwrap_or_default(),
            sol.family
        );
        round_trips(name, &rows, &sol, 100, 5);
        for k in 0..7 {
            let v = format!("q{}", k + 1);
            let mut locked: Vec<bool> = rows.iter().map(|r| r.prismatic).collect();
            locked.remove(k);
            let slides: Vec<usize> = (0..6).filter(|&i| locked[i]).collect();
            let three_apart = slides.len() == 2 && slides[1] - slides[0] == 3;
            match derive_free(name, &rows, Some(&v)) {
                Ok(sol) => {
                    eprintln!("{name}, --free {v}: {}", sol.family);
                    round_trips(name, &rows, &sol, 60, 11 + k as u64);
                }
                Err(e) => {
                    eprintln!("{name}, --free {v}: refused");
                    assert!(three_apart, "{name}, --free {v}: {e}");
                }
            }
        }
    }
}
