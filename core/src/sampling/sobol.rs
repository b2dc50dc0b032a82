//! The first two dimensions of the Sobol sequence, as 32-bit binary fractions.
//!
//! Point `i` of a digital sequence is the generator matrix times the bits of `i` over GF(2).
//! Dimension 0 is the van der Corput sequence (the matrix is the identity read backwards, so the
//! point is `i` with its bits reversed); dimension 1 uses the matrix of the primitive polynomial
//! `x + 1`, whose column `j` is the previous column XOR itself shifted right by one (Pascal's
//! triangle mod 2). Together they form a (0, 2)-sequence in base 2: every aligned block of `2^m`
//! consecutive indices is a (0, m, 2)-net, i.e. it has exactly one point in each elementary
//! interval `[a / 2^k, (a + 1) / 2^k) x [b / 2^(m-k), (b + 1) / 2^(m-k))`. Only the low 32 bits
//! of an index matter at 32-bit precision.

/// Column `j` of dimension 1's generator matrix (top bit = first binary digit).
const fn dim1_columns() -> [u32; 32] {
    let mut c = [0u32; 32];
    c[0] = 1 << 31;
    let mut j = 1;
    while j < 32 {
        c[j] = c[j - 1] ^ (c[j - 1] >> 1);
        j += 1;
    }
    c
}

/// `TABLE[b][v]`: XOR of the columns `8b..8b+8` of dimension 1 selected by the bits of byte `v`,
/// bit-reversed if `reversed`.
const fn dim1_tables(reversed: bool) -> [[u32; 256]; 4] {
    let mut cols = dim1_columns();
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

static DIM1: [[u32; 256]; 4] = dim1_tables(false);
static DIM1_REVERSED: [[u32; 256]; 4] = dim1_tables(true);

/// Dimension 0 of point `i` (van der Corput), as a fraction of 2^32.
#[inline]
pub fn sobol_dim0(i: u32) -> u32 {
    i.reverse_bits()
}

/// Dimension 1 of point `i`, as a fraction of 2^32.
#[inline]
pub fn sobol_dim1(i: u32) -> u32 {
    DIM1[0][(i & 0xff) as usize]
        ^ DIM1[1][((i >> 8) & 0xff) as usize]
        ^ DIM1[2][((i >> 16) & 0xff) as usize]
        ^ DIM1[3][(i >> 24) as usize]
}

/// Dimension 1 of point `i` with its bits reversed (what Owen scrambling works on).
#[inline]
pub fn sobol_dim1_reversed(i: u32) -> u32 {
    DIM1_REVERSED[0][(i & 0xff) as usize]
        ^ DIM1_REVERSED[1][((i >> 8) & 0xff) as usize]
        ^ DIM1_REVERSED[2][((i >> 16) & 0xff) as usize]
        ^ DIM1_REVERSED[3][(i >> 24) as usize]
}

/// Dimension 1 by the plain matrix-vector product (the tables' definition; for tests).
pub fn sobol_dim1_reference(mut i: u32) -> u32 {
    let cols = dim1_columns();
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
