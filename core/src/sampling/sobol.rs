//! The first four dimensions of the Sobol sequence, as 32-bit binary fractions.
//!
//! Point `i` of a digital sequence is the generator matrix times the bits of `i` over GF(2).
//! Dimension 0 is the van der Corput sequence (the matrix is the identity read backwards, so the
//! point is `i` with its bits reversed); dimension 1 uses the matrix of the primitive polynomial
//! `x + 1`, whose column `j` is the previous column XOR itself shifted right by one (Pascal's
//! triangle mod 2). Together they form a (0, 2)-sequence in base 2: every aligned block of `2^m`
//! consecutive indices is a (0, m, 2)-net, i.e. it has exactly one point in each elementary
//! interval `[a / 2^k, (a + 1) / 2^k) x [b / 2^(m-k), (b + 1) / 2^(m-k))`. Only the low 32 bits
//! of an index matter at 32-bit precision.
//!
//! Dimensions 2 and 3 use the polynomials `x^2 + x + 1` and `x^3 + x + 1` with the initial
//! direction numbers `1, 3` and `1, 3, 1` (Joe and Kuo's table, the standard choice). The four
//! dimensions together form a (3, 4)-sequence: every aligned block of `2^m` indices has exactly
//! `8` points in each elementary box of volume `2^(3-m)`; dimensions 2 and 3 alone form a
//! (2, 2)-sequence. The zsobol sampler uses them to draw two 2D points from one index.

/// Columns of a Sobol dimension's generator matrix (top bit = first binary digit): its
/// primitive polynomial has degree `s` and middle coefficients `a` (bit `s - 1 - i` is the
/// coefficient of `x^(s - i)`), and `m` holds its first `s` direction numbers (odd, below
/// `2^k` for the `k`-th).
const fn columns(s: usize, a: u32, m: &[u32]) -> [u32; 32] {
    let mut v = [0u32; 32];
    let mut k = 0;
    while k < s {
        v[k] = m[k] << (31 - k);
        k += 1;
    }
    while k < 32 {
        let mut x = v[k - s] ^ (v[k - s] >> s);
        let mut i = 1;
        while i < s {
            if (a >> (s - 1 - i)) & 1 != 0 {
                x ^= v[k - i];
            }
            i += 1;
        }
        v[k] = x;
        k += 1;
    }
    v
}

/// Generator columns of dimensions 1, 2 and 3.
const COLUMNS: [[u32; 32]; 3] = [
    columns(1, 0, &[1]),
    columns(2, 1, &[1, 3]),
    columns(3, 1, &[1, 3, 1]),
];

/// `TABLE[b][v]`: XOR of the columns `8b..8b+8` selected by the bits of byte `v`,
/// bit-reversed if `reversed`.
const fn tables(columns: [u32; 32], reversed: bool) -> [[u32; 256]; 4] {
    let mut cols = columns;
    if reversed {
        let mut j = 0;
        while j < 32 {
            cols[j] = cols[j].reverse_bits();
            j += 1;
        }
    }
    let mut t = [[0u32; 256]; 4];
    let mut b = 0;
    while b < 4 {
        let mut v = 0;
        while v < 256 {
            let mut x = 0u32;
            let mut k = 0;
            while k < 8 {
                if v & (1 << k) != 0 {
                    x ^= cols[8 * b + k];
                }
                k += 1;
            }
            t[b][v] = x;
            v += 1;
        }
        b += 1;
    }
    t
}

static DIM1: [[u32; 256]; 4] = tables(COLUMNS[0], false);

/// Dimensions 2 (low word) and 3 (high word), bit-reversed, in one table: a paired draw needs
/// both, and one pass of four lookups finds them.
static DIM23_REVERSED: [[u64; 256]; 4] = {
    let (a, b) = (tables(COLUMNS[1], true), tables(COLUMNS[2], true));
    let mut t = [[0u64; 256]; 4];
    let mut k = 0;
    while k < 4 {
        let mut v = 0;
        while v < 256 {
            t[k][v] = a[k][v] as u64 | (b[k][v] as u64) << 32;
            v += 1;
        }
        k += 1;
    }
    t
};

/// The XOR of a table's entries for the four bytes of `i`.
#[inline(always)]
fn lookup<T: Copy + core::ops::BitXor<Output = T>>(t: &[[T; 256]; 4], i: u32) -> T {
    t[0][(i & 0xff) as usize]
        ^ t[1][((i >> 8) & 0xff) as usize]
        ^ t[2][((i >> 16) & 0xff) as usize]
        ^ t[3][(i >> 24) as usize]
}

/// Dimension 0 of point `i` (van der Corput), as a fraction of 2^32.
#[inline]
pub fn sobol_dim0(i: u32) -> u32 {
    i.reverse_bits()
}

/// Dimension 1 of point `i`, as a fraction of 2^32.
#[inline]
pub fn sobol_dim1(i: u32) -> u32 {
    lookup(&DIM1, i)
}

/// Dimension 1 of point `i` with its bits reversed (what Owen scrambling works on). Column `k`
/// of the matrix holds the binomial coefficients `C(k, j)` mod 2, which are odd exactly when
/// the binary digits of `j` are among those of `k` (Lucas' theorem); so reversed bit `j` is the
/// parity of the bits of `i` at the positions `k` whose digits include `j`'s, which five
/// shift-and-XOR steps fold together (one per binary digit of a position). Shifts instead of
/// table lookups, so that eight lanes of it vectorise (`zsobol_lanes`).
#[inline(always)]
pub fn sobol_dim1_reversed(i: u32) -> u32 {
    let mut y = i;
    y ^= (y >> 1) & 0x5555_5555;
    y ^= (y >> 2) & 0x3333_3333;
    y ^= (y >> 4) & 0x0f0f_0f0f;
    y ^= (y >> 8) & 0x00ff_00ff;
    y ^= (y >> 16) & 0x0000_ffff;
    y
}

/// Dimensions 2 and 3 of point `i`, bit-reversed.
#[inline(always)]
pub fn sobol_dim23_reversed(i: u32) -> (u32, u32) {
    let both = lookup(&DIM23_REVERSED, i);
    (both as u32, (both >> 32) as u32)
}

/// Dimension 2 of point `i` with its bits reversed.
#[inline]
pub fn sobol_dim2_reversed(i: u32) -> u32 {
    sobol_dim23_reversed(i).0
}

/// Dimension 3 of point `i` with its bits reversed.
#[inline]
pub fn sobol_dim3_reversed(i: u32) -> u32 {
    sobol_dim23_reversed(i).1
}

/// Dimension `dim` (0 to 3) of point `i` by the plain matrix-vector product (the tables'
/// definition; for tests).
pub fn sobol_reference(dim: usize, mut i: u32) -> u32 {
    if dim == 0 {
        return i.reverse_bits();
    }
    let cols = COLUMNS[dim - 1];
    let mut x = 0;
    let mut j = 0;
    while i != 0 {
        if i & 1 != 0 {
            x ^= cols[j];
        }
        i >>= 1;
        j += 1;
    }
    x
}

/// Dimension 1 by the plain matrix-vector product.
pub fn sobol_dim1_reference(i: u32) -> u32 {
    sobol_reference(1, i)
}
