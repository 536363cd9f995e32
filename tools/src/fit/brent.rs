//! One-dimensional minimisation for the roughness search of [`super::fit`].

use super::FitError;

/// Brent's minimisation without derivatives (Brent 1973, "Algorithms for
/// minimization without derivatives", ch. 5): on `[a, b]` from the point `x`
/// with value `fx`, parabolic interpolation through the three best points
/// when its step is inside the bracket and shorter than half the step before
/// last, a golden-section step otherwise; stops when the bracket around the
/// best point is within `2 tol`. Returns the best abscissa.
pub(super) fn brent(
    mut a: f64,
    mut b: f64,
    x0: f64,
    fx0: f64,
    tol: f64,
    mut f: impl FnMut(f64) -> Result<f64, FitError>,
) -> Result<f64, FitError> {
    const C: f64 = 0.381_966_011_250_105_1; // (3 − √5)/2
    let (mut x, mut w, mut v) = (x0, x0, x0);
    let (mut fx, mut fw, mut fv) = (fx0, fx0, fx0);
    let (mut d, mut e) = (0.0f64, 0.0f64);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if (x - m).abs() <= 2.0 * tol - 0.5 * (b - a) {
            break;
        }
        let mut golden = true;
        if e.abs() > tol {
            // Parabola through (v, fv), (w, fw), (x, fx).
            let r = (x - w) * (fx - fv);
            let mut q = (x - v) * (fx - fw);
            let mut pnum = (x - v) * q - (x - w) * r;
            q = 2.0 * (q - r);
            if q > 0.0 {
                pnum = -pnum;
            }
            q = q.abs();
            if pnum.abs() < (0.5 * q * e).abs() && pnum > q * (a - x) && pnum < q * (b - x) {
                e = d;
                d = pnum / q;
                let u = x + d;
                if u - a < 2.0 * tol || b - u < 2.0 * tol {
                    d = if x < m { tol } else { -tol };
                }
                golden = false;
            }
        }
        if golden {
            e = if x < m { b - x } else { a - x };
            d = C * e;
        }
        let u = if d.abs() >= tol {
            x + d
        } else {
            x + tol.copysign(d)
        };
        let fu = f(u)?;
        if fu <= fx {
            if u < x {
                b = x;
            } else {
                a = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    Ok(x)
}
