//! Cyclic Jacobi eigen-decomposition of small symmetric matrices (used by the cone fit).

/// Eigenvalues and eigenvectors (columns of the returned matrix) of a symmetric matrix.
pub(crate) fn symmetric_eigen<const N: usize>(mut a: [[f64; N]; N]) -> ([f64; N], [[f64; N]; N]) {
    let mut v = [[0.0; N]; N];
    for (k, row) in v.iter_mut().enumerate() {
        row[k] = 1.0;
    }
    for sweep in 0..50 {
        let off: f64 = (0..N)
            .flat_map(|p| (p + 1..N).map(move |q| (p, q)))
            .map(|(p, q)| a[p][q].abs())
            .sum();
        if off == 0.0 || !off.is_finite() {
            break;
        }
        for p in 0..N {
            for q in p + 1..N {
                let apq = a[p][q];
                // After a few sweeps, off-diagonal entries below the rounding level of both diagonal
                // entries are set to zero (Numerical Recipes' criterion): guarantees termination.
                let g = 100.0 * apq.abs();
                if sweep > 3
                    && a[p][p].abs() + g == a[p][p].abs()
                    && a[q][q].abs() + g == a[q][q].abs()
                {
                    a[p][q] = 0.0;
                    a[q][p] = 0.0;
                    continue;
                }
                if apq == 0.0 {
                    continue;
                }
                let theta = (a[q][q] - a[p][p]) / (2.0 * apq);
                let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
                let t = if t.is_finite() { t } else { 0.0 };
                let c = 1.0 / (t * t + 1.0).sqrt();
                let s = t * c;
                for row in a.iter_mut() {
                    let (akp, akq) = (row[p], row[q]);
                    row[p] = c * akp - s * akq;
                    row[q] = s * akp + c * akq;
                }
                let (head, tail) = a.split_at_mut(q);
                for (x, y) in head[p].iter_mut().zip(tail[0].iter_mut()) {
                    let (apk, aqk) = (*x, *y);
                    *x = c * apk - s * aqk;
                    *y = s * apk + c * aqk;
                }
                for row in v.iter_mut() {
                    let (vkp, vkq) = (row[p], row[q]);
                    row[p] = c * vkp - s * vkq;
                    row[q] = s * vkp + c * vkq;
                }
            }
        }
    }
    let mut values = [0.0; N];
    for (k, value) in values.iter_mut().enumerate() {
        *value = a[k][k];
    }
    (values, v)
}

/// The unit eigenvector of the smallest eigenvalue.
pub(crate) fn smallest_eigenvector<const N: usize>(a: [[f64; N]; N]) -> [f64; N] {
    let (values, vectors) = symmetric_eigen(a);
    let k = (0..N)
        .min_by(|&x, &y| values[x].total_cmp(&values[y]))
        .unwrap_or(0);
    let mut out = [0.0; N];
    for (r, o) in out.iter_mut().enumerate() {
        *o = vectors[r][k];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decomposition_reconstructs_the_matrix() {
        let a = [
            [4.0, 1.0, -2.0, 0.5],
            [1.0, 3.0, 0.0, 1.5],
            [-2.0, 0.0, 5.0, -1.0],
            [0.5, 1.5, -1.0, 2.0],
        ];
        let (w, v) = symmetric_eigen(a);
        for r in 0..4 {
            for c in 0..4 {
                let s: f64 = (0..4).map(|k| v[r][k] * w[k] * v[c][k]).sum();
                assert!((s - a[r][c]).abs() < 1e-12, "({r},{c}): {s} vs {}", a[r][c]);
            }
        }
        let e = smallest_eigenvector(a);
        let min = w.iter().copied().fold(f64::INFINITY, f64::min);
        for r in 0..4 {
            let av: f64 = (0..4).map(|k| a[r][k] * e[k]).sum();
            assert!((av - min * e[r]).abs() < 1e-12);
        }
    }
}
