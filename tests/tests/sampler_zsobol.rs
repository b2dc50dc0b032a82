//! The zsobol sampler: exact stratification of each pixel's points, uniformity and independence
//! of its values pooled over pixels, determinism, and unbiased renders.
//!
//! - Stratification: for `N = 2^m` samples of one pixel, the 2D points of a dimension pair hit
//!   every elementary interval of area `1/N` (every shape `2^k x 2^(m-k)`) exactly once, and the
//!   1D values every interval `[i/N, (i+1)/N)` once; also for the first `2^m` samples of a pixel
//!   block of `2^20`. Controls: the points shifted by half a cell, an independent sampler's
//!   points, and a block size too small for the sample count all break it.
//! - Uniformity: chi-square tests (Sidak-corrected at 0.01 overall) of 1D and 2D histograms of
//!   several dimensions pooled over the pixels of an image (one sample per pixel: the samples of
//!   one pixel share their block and the per-dimension scramble, so pooling all of them would
//!   not give multinomial counts), and over many seeds at fixed pixels; 2D histograms of pairs
//!   of different dimensions test independence. Controls: a sampler that forgets to permute the
//!   index per dimension fails independence, one that ignores the pixel fails uniformity.
//! - Paired draws: the couples of 2D draws the layout pairs are 4D (3, m, 4)-nets per pixel
//!   (the second 2D point alone a (2, m, 2)-net); control: an unpaired couple is not.
//! - Determinism: a value is a pure function of (seed, K, pixel, sample, dimension).
//! - Rendering: closed-form scenes rendered with zsobol, t-tested across independent seeds (each
//!   seed's pixel mean is one independent, unbiased estimate; the samples within a pixel are
//!   not independent, so their sample variance would not be the estimate's variance).
use tessera_core::sampling::owen::{mix64, owen_scramble_u32, scramble_index};
use tessera_core::sampling::sobol::{
    sobol_dim0, sobol_dim1, sobol_dim1_reference, sobol_dim1_reversed, sobol_dim2_reversed,
    sobol_dim3_reversed, sobol_reference,
};
use tessera_core::sampling::zsobol::{log2_spp_for, to_unit};
use tessera_core::sampling::{IndependentSampler, Sampler, SamplerKind, ZSobolSampler};
use tessera_lab::stats::rng::Pcg32;
use tessera_lab::stats::{chi2_test, sidak_alpha, DEFAULT_MIN_EXPECTED};
use tessera_tests::load_xml;

/// Whether `pts` (N = 2^m points) has exactly one point in every elementary interval of every
/// shape `2^k x 2^(m-k)`.
fn is_02_net(pts: &[(f32, f32)], m: u32) -> bool {
    assert_eq!(pts.len(), 1 << m);
    (0..=m).all(|k| {
        let (nx, ny) = (1u64 << k, 1u64 << (m - k));
        let mut seen = vec![false; 1 << m];
        pts.iter().all(|&(x, y)| {
            let cx = ((x as f64 * nx as f64) as u64).min(nx - 1);
            let cy = ((y as f64 * ny as f64) as u64).min(ny - 1);
            let c = (cy * nx + cx) as usize;
            !std::mem::replace(&mut seen[c], true)
        })
    })
}

/// The 2D points of the first `n` samples of pixel `(x, y)` at the pair drawn after `before`
/// 1D draws (so the pair starts at dimension `before`).
fn pixel_points(seed: u64, x: u32, y: u32, n: u64, k: u32, before: u32) -> Vec<(f32, f32)> {
    (0..n)
        .map(|i| {
            let mut s = ZSobolSampler::new(seed, x, y, i, k);
            for _ in 0..before {
                s.next_1d();
            }
            let p = s.next_2d();
            (p.x, p.y)
        })
        .collect()
}

#[test]
fn sobol_tables_match_the_matrix_product() {
    let mut rng = Pcg32::new(5);
    for i in (0..4096).chain((0..4096).map(|_| rng.next_u32())) {
        assert_eq!(sobol_dim1(i), sobol_dim1_reference(i), "index {i}");
        // The folded form (shifts, no table) of the same matrix.
        assert_eq!(sobol_dim1_reversed(i).reverse_bits(), sobol_reference(1, i));
    }
    for i in (0..4096).chain((0..4096).map(|_| rng.next_u32())) {
        assert_eq!(sobol_dim2_reversed(i).reverse_bits(), sobol_reference(2, i));
        assert_eq!(sobol_dim3_reversed(i).reverse_bits(), sobol_reference(3, i));
    }
    // The first points of dimensions 2 and 3 (Joe and Kuo's direction numbers).
    let d2: Vec<u32> = (0..4).map(|i| sobol_reference(2, i)).collect();
    let d3: Vec<u32> = (0..4).map(|i| sobol_reference(3, i)).collect();
    assert_eq!(d2, [0, 1 << 31, 3 << 30, 1 << 30]);
    assert_eq!(d3, [0, 1 << 31, 3 << 30, 1 << 30]);
    assert_eq!(sobol_reference(2, 4), 0x6000_0000);
    assert_eq!(sobol_reference(3, 4), 0x2000_0000);
    // Known start of both dimensions.
    let d0: Vec<u32> = (0..4).map(sobol_dim0).collect();
    let d1: Vec<u32> = (0..4).map(sobol_dim1).collect();
    assert_eq!(d0, [0, 1 << 31, 1 << 30, 3 << 30]);
    assert_eq!(d1, [0, 1 << 31, 3 << 30, 1 << 30]);
}

#[test]
fn scrambles_are_nested_bijections() {
    // Values sharing their top j bits keep sharing them (and only them, bit j being flipped
    // the same way): aligned blocks go to aligned blocks.
    let mut rng = Pcg32::new(11);
    for _ in 0..2000 {
        let seed = rng.next_u32();
        let a = rng.next_u32();
        let j = rng.next_u32() % 32;
        let b = a ^ (1u32 << (31 - j)) ^ rng.next_u32().checked_shr(j + 1).unwrap_or(0);
        let (sa, sb) = (owen_scramble_u32(a, seed), owen_scramble_u32(b, seed));
        let top = |v: u32| if j == 0 { 0 } else { v >> (32 - j) };
        assert_eq!(top(sa), top(sb));
        assert_ne!((sa >> (31 - j)) & 1, (sb >> (31 - j)) & 1);
        // Indices of 32 + k bits.
        let k = rng.next_u32() % 33;
        let w = 32 + k;
        let seed64 = (rng.next_u32() as u64) << 32 | rng.next_u32() as u64;
        let a64 = ((rng.next_u32() as u64) << 32 | rng.next_u32() as u64) >> (64 - w);
        let j64 = rng.next_u32() % w;
        let b64 = a64
            ^ (1u64 << (w - 1 - j64))
            ^ (mix64(a64) >> (64 - w)).checked_shr(j64 + 1).unwrap_or(0);
        let (ia, ib) = (
            scramble_index(a64, k, seed64),
            scramble_index(b64, k, seed64),
        );
        assert!(ia.checked_shr(w).unwrap_or(0) == 0 && ib.checked_shr(w).unwrap_or(0) == 0);
        let top64 = |v: u64| v.checked_shr(w - j64).unwrap_or(0);
        assert_eq!(top64(ia), top64(ib), "k {k} j {j64}");
        assert_ne!((ia >> (w - 1 - j64)) & 1, (ib >> (w - 1 - j64)) & 1);
    }
    // A bijection on a full 2^16 block (8 pixel bits above 8 sample bits).
    let mut seen = vec![false; 1 << 16];
    let seed = 0x1234_5678_9abc_def0;
    for i in 0..1u64 << 16 {
        let p = scramble_index(i, 8, seed);
        assert!(p >> 16 == scramble_index(0, 8, seed) >> 16);
        assert!(!std::mem::replace(&mut seen[(p & 0xffff) as usize], true));
    }
}

#[test]
fn each_pixel_is_a_02_net() {
    let mut nets = 0;
    for (seed, x, y) in [
        (0u64, 0u32, 0u32),
        (7, 13, 5),
        (123, 1000, 3),
        (1, 65535, 65535),
    ] {
        for m in 0..=10u32 {
            let n = 1u64 << m;
            // Block of exactly N, and the first N samples of a block of 2^20.
            for k in [m, 20] {
                for before in [0u32, 9] {
                    let pts = pixel_points(seed, x, y, n, k, before);
                    assert!(
                        is_02_net(&pts, m),
                        "seed {seed} pixel ({x}, {y}) N {n} K {k} pair at {before}"
                    );
                    nets += 1;
                    // 1D values: one per interval of length 1/N.
                    let mut seen = vec![false; n as usize];
                    for i in 0..n {
                        let mut s = ZSobolSampler::new(seed, x, y, i, k);
                        for _ in 0..before + 2 {
                            s.next_1d();
                        }
                        let c = (s.next_1d() as f64 * n as f64) as usize;
                        assert!(!std::mem::replace(&mut seen[c], true));
                    }
                }
            }
        }
    }
    assert_eq!(nets, 4 * 11 * 2 * 2);
}

#[test]
fn controls_break_the_net_property() {
    let m = 8;
    let n = 1u64 << m;
    for (seed, x, y) in [(0u64, 0u32, 0u32), (7, 13, 5), (123, 1000, 3)] {
        let pts = pixel_points(seed, x, y, n, m, 0);
        assert!(is_02_net(&pts, m));
        // Shifted by half a cell of the finest column shape (mod 1).
        let shifted: Vec<(f32, f32)> = pts
            .iter()
            .map(|&(a, b)| (((a as f64 + 0.5 / n as f64) % 1.0) as f32, b))
            .collect();
        assert!(!is_02_net(&shifted, m), "shifted set still a net");
        // Independent points.
        let indep: Vec<(f32, f32)> = (0..n)
            .map(|i| {
                let p = IndependentSampler::new(seed, x, y, i).next_2d();
                (p.x, p.y)
            })
            .collect();
        assert!(!is_02_net(&indep, m), "independent points form a net");
        // A pixel block of N/2: two independently scrambled halves.
        let halves = pixel_points(seed, x, y, n, m - 1, 0);
        assert!(!is_02_net(&halves, m), "two half blocks form a net");
    }
}

/// Whether the `2^m` points `pts` (each `D` coordinates) form a `(t, m, D)`-net: exactly `2^t`
/// points in every elementary box of volume `2^(t - m)` (every split of `m - t` bits over the
/// coordinates).
fn is_net<const D: usize>(pts: &[[f32; D]], m: u32, t: u32) -> bool {
    assert_eq!(pts.len(), 1 << m);
    let t = t.min(m);
    let bits = m - t;
    // Every split of `bits` over the D coordinates.
    let mut splits = vec![[0u32; D]];
    for c in 0..D {
        splits = splits
            .into_iter()
            .flat_map(|s| {
                let used: u32 = s.iter().sum();
                (0..=bits - used).map(move |b| {
                    let mut s = s;
                    s[c] = b;
                    s
                })
            })
            .collect();
    }
    splits.retain(|s| s.iter().sum::<u32>() == bits);
    splits.iter().all(|split| {
        let mut count = vec![0u32; 1 << bits];
        for p in pts {
            let mut cell = 0u64;
            for c in 0..D {
                let n = 1u64 << split[c];
                let i = ((p[c] as f64 * n as f64) as u64).min(n - 1);
                cell = cell * n + i;
            }
            count[cell as usize] += 1;
        }
        count.iter().all(|&c| c == 1 << t)
    })
}

/// The couple of 2D draws at dimensions `a` and `b` of the first `n` samples of a pixel, as 4D
/// points.
fn couple(seed: u64, x: u32, y: u32, n: u64, k: u32, a: u32, b: u32) -> Vec<[f32; 4]> {
    (0..n)
        .map(|i| {
            let mut s = ZSobolSampler::new(seed, x, y, i, k);
            s.start_dimension(a);
            let p = s.next_2d();
            s.start_dimension(b);
            let q = s.next_2d();
            [p.x, p.y, q.x, q.y]
        })
        .collect()
}

/// The layout's couples (camera offset with the emitter position of bounce 0, the BSDF
/// direction of bounce `d` with the emitter position of bounce `d + 1`) are 4D (3, m, 4)-nets
/// per pixel, their second halves (2, m, 2)-nets, their first halves still (0, m, 2)-nets; the
/// same holds through the per-pixel cache. Control: two unpaired 2D draws (joined at random)
/// are not (3, m, 4)-nets.
#[test]
fn paired_draws_are_4d_nets() {
    use tessera_core::sampling::{dimension_of, Stage, ZSobolPixel};
    let light = |d: u32| dimension_of(d, Stage::Light) + 1;
    let bsdf = |d: u32| dimension_of(d, Stage::Bsdf) + 1;
    let couples = [(0, light(0)), (bsdf(0), light(1)), (bsdf(3), light(4))];
    for (seed, x, y) in [(0u64, 0u32, 0u32), (7, 13, 5), (123, 1000, 3)] {
        for m in 0..=9u32 {
            let n = 1u64 << m;
            for k in [m, 20] {
                for &(a, b) in &couples {
                    let pts = couple(seed, x, y, n, k, a, b);
                    let what = format!("seed {seed} pixel ({x}, {y}) N {n} K {k} dims {a}+{b}");
                    assert!(is_net(&pts, m, 3), "4D: {what}");
                    let first: Vec<[f32; 2]> = pts.iter().map(|p| [p[0], p[1]]).collect();
                    let second: Vec<[f32; 2]> = pts.iter().map(|p| [p[2], p[3]]).collect();
                    assert!(is_net(&first, m, 0), "first: {what}");
                    assert!(is_net(&second, m, 2), "second: {what}");
                    // The cached sampler draws the same couple.
                    let mut px = ZSobolPixel::new(seed, x, y, k);
                    for (i, p) in pts.iter().enumerate() {
                        let mut s = px.sampler(i as u64);
                        s.start_dimension(a);
                        let u = s.next_2d();
                        s.start_dimension(b);
                        let v = s.next_2d();
                        assert_eq!([u.x, u.y, v.x, v.y], *p, "{what}");
                    }
                }
            }
        }
        // Control: the camera offset with an unpaired 2D draw.
        let m = 9;
        let unpaired = couple(seed, x, y, 1 << m, m, 0, bsdf(0));
        assert!(!is_net(&unpaired, m, 3), "unpaired draws form a 4D net");
        assert!(
            is_net(&unpaired, m, m),
            "the checker accepts any set at t = m"
        );
    }
}

/// One sample of every pixel of a `res x res` image (sample index `hash(pixel) mod spp`):
/// `value(x, y, i)` gives one row of columns per sample. All samples of one pixel share their
/// higher index bits and every pixel shares the per-dimension value scramble, so the values of
/// a pixel's samples are far from independent (pooling them all would not give multinomial
/// counts); one per pixel does.
fn one_per_pixel(res: u32, spp: u64, value: impl Fn(u32, u32, u64) -> Vec<f32>) -> Vec<Vec<f32>> {
    let mut out: Vec<Vec<f32>> = Vec::new();
    for y in 0..res {
        for x in 0..res {
            let i = mix64(((x as u64) << 32) | y as u64) % spp;
            let row = value(x, y, i);
            out.resize(row.len(), Vec::new());
            for (c, v) in row.into_iter().enumerate() {
                out[c].push(v);
            }
        }
    }
    out
}

/// The request pattern used by the uniformity tests, like a path tracer's: camera 2D, then per
/// bounce 1D, 2D (light), 1D, 2D (BSDF), and a 1D roulette value.
const PATTERN: [bool; 14] = [
    true, false, true, false, true, false, false, true, false, true, false, false, true, false,
];

/// The values of sample `i` of pixel `(x, y)` under `seed` along [`PATTERN`].
fn zsobol_row(seed: u64, x: u32, y: u32, i: u64, k: u32) -> Vec<f32> {
    let mut s = ZSobolSampler::new(seed, x, y, i, k);
    let mut v = Vec::new();
    for &two in &PATTERN {
        if two {
            let p = s.next_2d();
            v.extend([p.x, p.y]);
        } else {
            v.push(s.next_1d());
        }
    }
    v
}

/// p-value of a 1D histogram of `v` in `bins` equal bins.
fn p_1d(v: &[f32], bins: usize) -> f64 {
    let mut obs = vec![0.0; bins];
    for &x in v {
        obs[((x as f64 * bins as f64) as usize).min(bins - 1)] += 1.0;
    }
    let exp = vec![v.len() as f64 / bins as f64; bins];
    chi2_test(&obs, &exp, DEFAULT_MIN_EXPECTED).p_value
}

/// p-value of a 2D histogram of `(a, b)` in `bins x bins` equal cells.
fn p_2d(a: &[f32], b: &[f32], bins: usize) -> f64 {
    let mut obs = vec![0.0; bins * bins];
    for (&x, &y) in a.iter().zip(b) {
        let cx = ((x as f64 * bins as f64) as usize).min(bins - 1);
        let cy = ((y as f64 * bins as f64) as usize).min(bins - 1);
        obs[cy * bins + cx] += 1.0;
    }
    let exp = vec![a.len() as f64 / (bins * bins) as f64; bins * bins];
    chi2_test(&obs, &exp, DEFAULT_MIN_EXPECTED).p_value
}

/// Column pairs tested for independence: different dimensions (1D with 1D, 1D with a 2D
/// coordinate, coordinates of different 2D draws), and the two coordinates of one 2D draw.
const PAIRS: [(usize, usize); 8] = [
    (2, 5),
    (2, 3),
    (0, 2),
    (0, 4),
    (5, 10),
    (3, 7),
    (0, 1),
    (8, 9),
];

/// Runs every uniformity test on `cols`; returns the smallest p-value and where.
fn uniformity(cols: &[Vec<f32>]) -> (f64, String) {
    let mut worst = (1.0, String::new());
    let mut note = |p: f64, what: String| {
        if p < worst.0 {
            worst = (p, what);
        }
    };
    for (c, v) in cols.iter().enumerate() {
        note(p_1d(v, 64), format!("1D column {c}"));
    }
    for &(a, b) in &PAIRS {
        note(
            p_2d(&cols[a], &cols[b], 16),
            format!("2D columns ({a}, {b})"),
        );
    }
    worst
}

fn n_uniformity_tests(cols: usize) -> usize {
    cols + PAIRS.len()
}

#[test]
fn values_are_uniform_and_independent() {
    let cols = PATTERN
        .iter()
        .map(|&t| if t { 2 } else { 1 })
        .sum::<usize>();
    // Pooled over the pixels of one image: K matching 16 spp, the first 16 samples of a 2^20
    // block (the bench's setting), and 1 spp. Then over 2^16 seeds at fixed pixels and samples
    // (exactly independent draws of the randomization).
    let settings = [(3u64, 16u64, 4u32), (9, 16, 20), (2, 1, 0)];
    let fixed = [
        (0u32, 0u32, 0u64, 4u32),
        (37, 501, 13, 4),
        (5, 6, 70_000, 20),
    ];
    let alpha = sidak_alpha(
        0.01,
        (settings.len() + fixed.len()) * n_uniformity_tests(cols),
    );
    for (seed, spp, k) in settings {
        let data = one_per_pixel(256, spp, |x, y, i| zsobol_row(seed, x, y, i, k));
        assert_eq!(data.len(), cols);
        let (p, what) = uniformity(&data);
        eprintln!("seed {seed} spp {spp} K {k}: smallest p {p:.3e} ({what})");
        assert!(
            p >= alpha,
            "seed {seed} spp {spp} K {k}: {what} p = {p:.3e} < {alpha:.3e}"
        );
    }
    for (x, y, i, k) in fixed {
        let mut data: Vec<Vec<f32>> = vec![Vec::new(); cols];
        for seed in 0..1u64 << 16 {
            for (c, v) in zsobol_row(seed, x, y, i, k).into_iter().enumerate() {
                data[c].push(v);
            }
        }
        let (p, what) = uniformity(&data);
        eprintln!("over seeds, pixel ({x}, {y}) sample {i} K {k}: smallest p {p:.3e} ({what})");
        assert!(
            p >= alpha,
            "over seeds, pixel ({x}, {y}) sample {i} K {k}: {what} p = {p:.3e} < {alpha:.3e}"
        );
    }
}

#[test]
fn controls_fail_uniformity() {
    let alpha = sidak_alpha(0.01, 8);
    // Forgets to permute the index per dimension: each dimension's value is an Owen scramble of
    // the same Sobol point, so two dimensions are a fixed function of each other.
    let same_index = |x: u32, y: u32, i: u64| {
        let s = ZSobolSampler::new(3, x, y, i, 4);
        let idx = s.morton_index() as u32;
        (0..4)
            .map(|d| to_unit(owen_scramble_u32(sobol_dim0(idx), s.draw(d).seed_x)))
            .collect::<Vec<f32>>()
    };
    let data = one_per_pixel(256, 16, same_index);
    let p = p_2d(&data[0], &data[1], 16);
    eprintln!("control, unpermuted index: p = {p:.3e}");
    assert!(
        p < alpha,
        "unpermuted index passes independence: p = {p:.3e}"
    );
    // Ignores the pixel: every pixel repeats the same 16 points.
    let no_pixel = |_x: u32, _y: u32, i: u64| {
        let mut s = ZSobolSampler::new(3, 0, 0, i, 4);
        vec![s.next_1d()]
    };
    let data = one_per_pixel(256, 16, no_pixel);
    let p = p_1d(&data[0], 64);
    eprintln!("control, pixel-blind: p = {p:.3e}");
    assert!(
        p < alpha,
        "pixel-blind sampler passes uniformity: p = {p:.3e}"
    );
}

#[test]
fn values_are_a_pure_function_of_their_inputs() {
    let draw = |seed, x, y, i, k| {
        let mut s = ZSobolSampler::new(seed, x, y, i, k);
        let mut v: Vec<u32> = (0..6).map(|_| s.next_1d().to_bits()).collect();
        let p = s.next_2d();
        v.extend([p.x.to_bits(), p.y.to_bits()]);
        assert_eq!(s.dimension(), 8);
        v
    };
    let a = draw(5, 10, 20, 3, 6);
    assert_eq!(a, draw(5, 10, 20, 3, 6));
    // Direct evaluation of a dimension equals drawing up to it.
    let s = ZSobolSampler::new(5, 10, 20, 3, 6);
    assert_eq!(to_unit(s.value_1d(4)).to_bits(), a[4]);
    for other in [
        draw(6, 10, 20, 3, 6),
        draw(5, 11, 20, 3, 6),
        draw(5, 10, 21, 3, 6),
        draw(5, 10, 20, 4, 6),
        draw(5, 10, 20, 3, 7),
        draw(5, 10, 20, 3 + 64, 6),
    ] {
        assert_ne!(a, other);
    }
    // Values lie in [0, 1).
    for i in 0..1000 {
        let mut s = ZSobolSampler::new(i, i as u32, 0, i, 3);
        for _ in 0..20 {
            let v = s.next_1d();
            assert!((0.0..1.0).contains(&v));
        }
    }
    assert_eq!(
        [0, 1, 2, 3, 4, 5, 64, 65, u64::MAX].map(log2_spp_for),
        [0, 0, 1, 2, 2, 3, 6, 7, 32]
    );
}

#[test]
fn scene_files_choose_the_sampler() {
    let xml = |kind: &str| {
        format!(
            r#"<scene version="3.0.0">
  <sensor type="perspective">
    <film type="hdrfilm"><integer name="width" value="2"/><integer name="height" value="2"/></film>
    <sampler type="{kind}"><integer name="sample_count" value="100"/></sampler>
  </sensor>
</scene>"#
        )
    };
    assert_eq!(
        load_xml(&xml("zsobol"), &[]).scene.sampler,
        SamplerKind::ZSobol { log2_spp: 7 }
    );
    assert_eq!(
        load_xml(&xml("independent"), &[]).scene.sampler,
        SamplerKind::Independent
    );
    let l = load_xml(&xml("ldsampler"), &[]);
    assert_eq!(l.scene.sampler, SamplerKind::ZSobol { log2_spp: 7 });
    assert!(
        l.warnings.iter().any(|w| w.contains("zsobol")),
        "{:?}",
        l.warnings
    );
    let path = tessera_tests::scenes_dir().join("inline-test.xml");
    let err = tessera_scene::load_scene_str(&xml("sobol"), &path, &[])
        .expect_err("unknown sampler is an error")
        .to_string();
    assert!(err.contains("inline-test.xml:4:5"), "{err}");
    assert!(err.contains("unknown sampler \"sobol\""), "{err}");
    // Without a sampler: zsobol with the largest block, kept whatever count is asked for.
    let none = r#"<scene version="3.0.0"><sensor type="perspective"/></scene>"#;
    let mut l = load_xml(none, &[]);
    let largest = SamplerKind::ZSobol { log2_spp: 32 };
    assert_eq!(
        (l.scene.sampler, l.spp, l.sampler_named),
        (largest, 4, false)
    );
    l.set_sampler(None, 64).expect("keep the default");
    assert_eq!(l.scene.sampler, largest);
    l.set_sampler(Some("zsobol"), 64).expect("zsobol by name");
    assert_eq!(l.scene.sampler, SamplerKind::ZSobol { log2_spp: 6 });
    // A file's own zsobol follows the count it is set up for.
    let mut l = load_xml(&xml("zsobol"), &[]);
    l.set_sampler(None, 16).expect("keep the file's");
    assert_eq!(l.scene.sampler, SamplerKind::ZSobol { log2_spp: 4 });
}
