//! Closed forms of the shapes of issue 33's held-out corpus (`scripts/heldout_corpus.py`),
//! written here with other symbols, offsets and coefficients than any seed of it: squares of
//! sums (`closed/square.rs`), a factor shared by the summands of a sum of products, a sum
//! split by its angles' symbols, and pairs of summands joined, also inside products
//! (`closed/extra.rs`). Every case: the input is expanded into its
//! canonical (Fourier) form, the closed form found from that equals it exactly, its f64 value
//! at random points equals a formula written here (plain `f64::cos` and `f64::sin`), and it
//! has the short shape (a square, a shared factor taken out) as printed.

use crate::common::Rng;
use dqsym::{closed_form, eval_scalar_text, plain, PlainOptions};

type F = fn(&dyn Fn(&str) -> f64) -> f64;

/// The closed form of `input` expanded: exact, at 10 random points equal to `direct`, and
/// printed as `want`.
fn check(input: &str, want: &str, direct: F) {
    let x = eval_scalar_text(input).unwrap_or_else(|e| panic!("{input}: {e}"));
    let e = closed_form(&x).unwrap_or_else(|err| panic!("{input}: {err}"));
    assert_eq!(e.to_scalar(), x, "{input}");
    let mut g = Rng::new(0x51_7cc1_b727_220a ^ input.len() as u64);
    for _ in 0..10 {
        let vals: Vec<(String, f64)> = e
            .symbol_names()
            .into_iter()
            .map(|n| (n, g.range(-2.0, 2.0)))
            .collect();
        let env = |n: &str| {
            vals.iter()
                .find(|(m, _)| m == n)
                .map(|(_, v)| *v)
                .unwrap_or_else(|| panic!("no value for {n}"))
        };
        let pairs: Vec<(&str, f64)> = vals.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        let got = e.value_at(&pairs).expect("value");
        let want_v = direct(&env);
        // A few dozen f64 operations on values of size ~1 (lengths below 2): well under 1e-9.
        assert!(
            (got - want_v).abs() < 1e-9 * (1.0 + want_v.abs()),
            "{input}: {got} vs {want_v}"
        );
    }
    assert_eq!(plain(&e, &PlainOptions::default()), want, "{input}");
}

#[test]
fn a_square_of_a_length_times_a_cosine_and_a_sine_is_found() {
    check("(m*cos(a) - sin(b))^2", "(m cos(a) - sin(b))^2", |v| {
        (v("m") * v("a").cos() - v("b").sin()).powi(2)
    });
}

#[test]
fn a_square_with_an_offset_and_half_angles_is_found() {
    check(
        "(n*cos(a/2 + pi/6) + sin(2*c))^2",
        "(sin(2*c) + n cos(a/2 + pi/6))^2",
        |v| {
            (v("n") * (v("a") / 2.0 + std::f64::consts::PI / 6.0).cos() + (2.0 * v("c")).sin())
                .powi(2)
        },
    );
}

#[test]
fn minus_a_square_times_a_length_and_a_number_is_found() {
    check(
        "-3*m*(cos(a - b) + n*sin(c + a))^2",
        "-3 m (cos(a - b) + n sin(a + c))^2",
        |v| -3.0 * v("m") * ((v("a") - v("b")).cos() + v("n") * (v("c") + v("a")).sin()).powi(2),
    );
}

#[test]
fn a_square_with_a_quarter_turn_offset_is_found() {
    check(
        "(m*cos(a - c + pi/4) + sin(b/2 + c))^2",
        "(sin(b/2 + c) + m cos(a - c + pi/4))^2",
        |v| {
            (v("m") * (v("a") - v("c") + std::f64::consts::FRAC_PI_4).cos()
                + (v("b") / 2.0 + v("c")).sin())
            .powi(2)
        },
    );
}

#[test]
fn a_length_shared_by_two_products_is_taken_out() {
    check(
        "n*cos(c/2 - pi/3)*sin(c) - n*sin(a/2 + b)*cos(d)",
        "n (cos(c/2 - pi/3) sin(c) - sin(a/2 + b) cos(d))",
        |v| {
            v("n")
                * ((v("c") / 2.0 - std::f64::consts::FRAC_PI_3).cos() * v("c").sin()
                    - (v("a") / 2.0 + v("b")).sin() * v("d").cos())
        },
    );
}

#[test]
fn a_sum_whose_parts_share_a_symbol_is_split_by_the_symbols_of_its_angles() {
    check(
        "2*sin(a/2)*sin(a - b) - sin(c)*cos(d)*cos(a)",
        "2 sin(a - b) sin(a/2) - cos(a) sin(c) cos(d)",
        |v| {
            2.0 * (v("a") / 2.0).sin() * (v("a") - v("b")).sin()
                - v("c").sin() * v("d").cos() * v("a").cos()
        },
    );
}

#[test]
fn two_cosines_of_equal_weight_are_joined_into_a_product_and_one_minus_a_cosine_into_a_square() {
    // cos(a - b/2 + pi/4) cos(b) expands to two cosines at pi/4 offsets (radicals in the
    // canonical form), 2 sin(c)^2 to 1 - cos(2 c): the closed form joins both pairs again.
    check(
        "2*cos(a - b/2 + pi/4)*cos(b) + 2*sin(c)^2",
        "2 (cos(a - b/2 + pi/4) cos(b) + sin(c)^2)",
        |v| {
            2.0 * (v("a") - v("b") / 2.0 + std::f64::consts::FRAC_PI_4).cos() * v("b").cos()
                + 2.0 * v("c").sin().powi(2)
        },
    );
}

#[test]
fn minus_a_number_times_a_square_of_a_sine_is_kept_a_square() {
    // The sign is the number's: `-3/4 sin(a)^2` (4 operations), not `3/8 (cos(2 a) - 1)`.
    check("-3*sin(a)^2/4", "-3/4 sin(a)^2", |v| {
        -0.75 * v("a").sin().powi(2)
    });
}

#[test]
fn two_sines_inside_a_product_are_joined_into_a_product() {
    // sin(c) sin(a + b) cos(a) expands to sin(c) (sin(2 a + b) + sin(b))/2: the sum inside
    // the product is joined again (sum to product), the numbers' factor 2 taken out.
    check(
        "sin(c)*sin(a + b)*cos(a)/2 + sin(d/2)*cos(2*a + e)/2",
        "1/2 (sin(c) sin(a + b) cos(a) + cos(2*a + e) sin(d/2))",
        |v| {
            0.5 * v("c").sin() * (v("a") + v("b")).sin() * v("a").cos()
                + 0.5 * (v("d") / 2.0).sin() * (2.0 * v("a") + v("e")).cos()
        },
    );
}

#[test]
fn two_cosines_inside_a_product_are_joined_into_two_sines() {
    // cos(A) - cos(B) = -2 sin((A + B)/2) sin((A - B)/2) inside the product with sin(a/3).
    check(
        "-sin(a/3)*sin(b + c)*sin(c - d) - 2*sin(d)*sin(e/2)",
        "-sin(a/3) sin(b + c) sin(c - d) - 2 sin(d) sin(e/2)",
        |v| {
            -(v("a") / 3.0).sin() * (v("b") + v("c")).sin() * (v("c") - v("d")).sin()
                - 2.0 * v("d").sin() * (v("e") / 2.0).sin()
        },
    );
}

#[test]
fn a_cosine_and_a_sine_of_one_angle_inside_a_product_are_one_sinusoid() {
    // sin(a + pi/6) is (sqrt(3) sin(a) + cos(a))/2 in the canonical form: the harmonic form
    // inside the product joins them again (2 cos(a - pi/3)); sqrt(2) (cos(a) - sin(a)), as
    // short as sqrt(2) cos(a + pi/4) counted alone, is joined inside its product, whose
    // sqrt(2) makes it 2 cos(a + pi/4); the numbers' 1/2 and 2 then cancel.
    check(
        "m*(sin(c)*sin(b)*sin(a + pi/6) + sin(2*c + 2*b)*cos(a + pi/4))",
        "m (sin(b) sin(c) cos(a - pi/3) + sin(2*b + 2*c) cos(a + pi/4))",
        |v| {
            v("m")
                * (v("c").sin() * v("b").sin() * (v("a") + std::f64::consts::FRAC_PI_6).sin()
                    + (2.0 * v("c") + 2.0 * v("b")).sin()
                        * (v("a") + std::f64::consts::FRAC_PI_4).cos())
        },
    );
}

#[test]
fn two_sines_whose_factors_differ_in_sign_are_joined() {
    // The z entry of the symbolic screw's pow(q, t, psi) (snapshots/dqr_symbolic_screw): the
    // factors a - 2 b and -a + 2 b differ only in sign, so sin(psi/2) - sin(psi/2 - theta)
    // joins: 2 cos((psi - theta)/2) sin(theta/2).
    check(
        "1/18*t*(cos(psi/2)*(4*a + 2*b + 5*c - 6*d) - cos(psi/2 - theta)*(4*a + 2*b + 5*c) \
         + 3*(sin(psi/2)*(a - 2*b) + sin(psi/2 - theta)*(-a + 2*b)))",
        "1/18 t (cos(psi/2) (4 a + 2 b + 5 c - 6 d) - cos(psi/2 - theta) (4 a + 2 b + 5 c) \
         + 6 (a - 2 b) cos((psi - theta)/2) sin(theta/2))",
        |v| {
            let (a, b, c, d) = (v("a"), v("b"), v("c"), v("d"));
            let (psi, theta) = (v("psi"), v("theta"));
            v("t") / 18.0
                * ((psi / 2.0).cos() * (4.0 * a + 2.0 * b + 5.0 * c - 6.0 * d)
                    - (psi / 2.0 - theta).cos() * (4.0 * a + 2.0 * b + 5.0 * c)
                    + 3.0
                        * ((psi / 2.0).sin() * (a - 2.0 * b)
                            + (psi / 2.0 - theta).sin() * (-a + 2.0 * b)))
        },
    );
}

#[test]
fn a_sum_shared_up_to_its_sign_is_taken_out() {
    // x (a - b) + y (b - a) = (x - y) (a - b).
    check("x*(a - b) + y*(b - a)", "(x - y) (a - b)", |v| {
        v("x") * (v("a") - v("b")) + v("y") * (v("b") - v("a"))
    });
}
