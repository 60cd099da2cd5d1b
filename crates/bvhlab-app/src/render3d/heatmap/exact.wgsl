// Exact arithmetic for the heat map's compute shader: the `f64` steps of the core's watertight
// ray-triangle test, and correctly rounded `f32` division, in 32-bit integer operations.
//
// WGSL has no `f64`, and WebGPU allows `x / y` an error of 2.5 units in the last place, so the
// shader cannot rely on either to reproduce the CPU's bits. Here every result is rounded
// exactly once, to nearest with ties to even, as IEEE 754 binary64 (or binary32) does:
// - a value is a sign, an exponent and a 64-bit significand `m` (two u32 words, high word
//   first) normalised so that bit 63 is set; `m = 0` is zero (whose sign is not kept: no
//   decision of the core depends on the sign of a zero);
// - an operation computes the exact result's leading bits plus a sticky bit (the OR of every
//   bit below them), then `f64_round` keeps 53 bits.
// The inputs are `f32` values and products of at most three of them, so the binary64
// exponent never overflows or underflows and subnormal binary64 values never occur.

// --- 64-bit unsigned integers as vec2<u32>(high word, low word) ---

fn u64_is_zero(a: vec2<u32>) -> bool {
    return (a.x | a.y) == 0u;
}

fn u64_ge(a: vec2<u32>, b: vec2<u32>) -> bool {
    return a.x > b.x || (a.x == b.x && a.y >= b.y);
}

fn u64_add(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {
    let lo = a.y + b.y;
    return vec2<u32>(a.x + b.x + select(0u, 1u, lo < a.y), lo);
}

// a − b for a ≥ b.
fn u64_sub(a: vec2<u32>, b: vec2<u32>) -> vec2<u32> {
    return vec2<u32>(a.x - b.x - select(0u, 1u, a.y < b.y), a.y - b.y);
}

fn u64_clz(a: vec2<u32>) -> u32 {
    if a.x != 0u {
        return countLeadingZeros(a.x);
    }
    return 32u + countLeadingZeros(a.y);
}

// a << s for s < 64 (WGSL shifts take their amount modulo 32, so each case is explicit).
fn u64_shl(a: vec2<u32>, s: u32) -> vec2<u32> {
    if s == 0u {
        return a;
    }
    if s >= 32u {
        return vec2<u32>(a.y << (s - 32u), 0u);
    }
    return vec2<u32>((a.x << s) | (a.y >> (32u - s)), a.y << s);
}

// a >> s, with every bit shifted out OR-ed into bit 0 (the sticky bit).
fn u64_shr_sticky(a: vec2<u32>, s: u32) -> vec2<u32> {
    if s == 0u {
        return a;
    }
    if s >= 64u {
        return vec2<u32>(0u, select(0u, 1u, !u64_is_zero(a)));
    }
    var out: vec2<u32>;
    var lost: u32;
    if s == 32u {
        out = vec2<u32>(0u, a.x);
        lost = a.y;
    } else if s > 32u {
        out = vec2<u32>(0u, a.x >> (s - 32u));
        lost = a.y | (a.x << (64u - s));
    } else {
        out = vec2<u32>(a.x >> s, (a.y >> s) | (a.x << (32u - s)));
        lost = a.y << (32u - s);
    }
    out.y = out.y | select(0u, 1u, lost != 0u);
    return out;
}

// --- binary64 ---

// ±m · 2^(e − 63), with bit 63 of m set, or zero (m = 0).
struct F64 {
    neg: bool,
    e: i32,
    m: vec2<u32>,
}

fn f64_zero() -> F64 {
    return F64(false, 0, vec2<u32>(0u, 0u));
}

fn f64_is_zero(a: F64) -> bool {
    return u64_is_zero(a.m);
}

// Whether a < 0 (a zero is neither negative nor positive).
fn f64_negative(a: F64) -> bool {
    return a.neg && !f64_is_zero(a);
}

fn f64_positive(a: F64) -> bool {
    return !a.neg && !f64_is_zero(a);
}

// The f32 `x` exactly (subnormal inputs included; infinities and NaN are not expected).
fn f64_from_f32(x: f32) -> F64 {
    let bits = bitcast<u32>(x);
    let biased = i32((bits >> 23u) & 0xffu);
    var m = bits & 0x7fffffu;
    var e = -126;
    if biased != 0 {
        m = m | 0x800000u;
        e = biased - 127;
    }
    if m == 0u {
        return f64_zero();
    }
    // x = m · 2^(e − 23); moving m's top bit to bit 63 of the significand.
    let z = countLeadingZeros(m);
    return F64((bits >> 31u) != 0u, e + 8 - i32(z), vec2<u32>(m << z, 0u));
}

// Rounds a normalised significand (bit 63 set; bit 0 may carry the sticky bit) to 53 bits,
// to nearest, ties to even.
fn f64_round(neg: bool, e: i32, m: vec2<u32>) -> F64 {
    let rest = m.y & 0x7ffu;
    var r = vec2<u32>(m.x, m.y & ~0x7ffu);
    if rest > 0x400u || (rest == 0x400u && (r.y & 0x800u) != 0u) {
        r = u64_add(r, vec2<u32>(0u, 0x800u));
        if u64_is_zero(r) {
            return F64(neg, e + 1, vec2<u32>(0x80000000u, 0u));
        }
    }
    return F64(neg, e, r);
}

// a · b, rounded.
fn f64_mul(a: F64, b: F64) -> F64 {
    if f64_is_zero(a) || f64_is_zero(b) {
        return f64_zero();
    }
    // Schoolbook product of 16-bit limbs (least significant first): each limb product fits a
    // u32, and so does each column sum with its carry.
    var x = array<u32, 4>(a.m.y & 0xffffu, a.m.y >> 16u, a.m.x & 0xffffu, a.m.x >> 16u);
    var y = array<u32, 4>(b.m.y & 0xffffu, b.m.y >> 16u, b.m.x & 0xffffu, b.m.x >> 16u);
    var p = array<u32, 8>(0u, 0u, 0u, 0u, 0u, 0u, 0u, 0u);
    for (var i = 0u; i < 4u; i++) {
        var carry = 0u;
        for (var j = 0u; j < 4u; j++) {
            let t = x[i] * y[j];
            let s = p[i + j] + (t & 0xffffu) + carry;
            p[i + j] = s & 0xffffu;
            carry = (t >> 16u) + (s >> 16u);
        }
        p[i + 4u] = carry;
    }
    let w3 = (p[7] << 16u) | p[6];
    let w2 = (p[5] << 16u) | p[4];
    let w1 = (p[3] << 16u) | p[2];
    let w0 = (p[1] << 16u) | p[0];
    let neg = a.neg != b.neg;
    // The 128-bit product has its top bit at 127 or 126.
    if (w3 & 0x80000000u) != 0u {
        let m = vec2<u32>(w3, w2 | select(0u, 1u, (w1 | w0) != 0u));
        return f64_round(neg, a.e + b.e + 1, m);
    }
    let sticky = select(0u, 1u, ((w1 << 1u) | w0) != 0u);
    let m = vec2<u32>((w3 << 1u) | (w2 >> 31u), (w2 << 1u) | (w1 >> 31u) | sticky);
    return f64_round(neg, a.e + b.e, m);
}

// a + b, rounded. Both are rounded values (their low 11 bits are zero), so aligning them
// with a one-bit headroom loses nothing unless the exponents differ by 2 or more, and then the
// sticky bit below the ten guard bits decides the rounding exactly.
fn f64_add(a: F64, b: F64) -> F64 {
    if f64_is_zero(a) {
        return b;
    }
    if f64_is_zero(b) {
        return a;
    }
    var big = a;
    var small = b;
    if b.e > a.e || (b.e == a.e && !u64_ge(a.m, b.m)) {
        big = b;
        small = a;
    }
    let x = u64_shr_sticky(big.m, 1u);
    let y = u64_shr_sticky(small.m, min(u32(big.e - small.e), 63u) + 1u);
    var s: vec2<u32>;
    if big.neg == small.neg {
        s = u64_add(x, y);
    } else {
        s = u64_sub(x, y);
        if u64_is_zero(s) {
            return f64_zero();
        }
    }
    let z = u64_clz(s);
    return f64_round(big.neg, big.e + 1 - i32(z), u64_shl(s, z));
}

fn f64_sub(a: F64, b: F64) -> F64 {
    return f64_add(a, F64(!b.neg, b.e, b.m));
}

// a / b for b ≠ 0, rounded: long division of the 53-bit significands to 55 quotient bits
// (the last two are the guard bits) and a sticky bit for a nonzero remainder.
fn f64_div(a: F64, b: F64) -> F64 {
    if f64_is_zero(a) {
        return f64_zero();
    }
    var r = u64_shr_sticky(a.m, 11u);
    let d = u64_shr_sticky(b.m, 11u);
    var e = a.e - b.e;
    if !u64_ge(r, d) {
        r = u64_shl(r, 1u);
        e = e - 1;
    }
    var q = vec2<u32>(0u, 0u);
    for (var i = 0u; i < 55u; i++) {
        q = u64_shl(q, 1u);
        if u64_ge(r, d) {
            r = u64_sub(r, d);
            q.y = q.y | 1u;
        }
        r = u64_shl(r, 1u);
    }
    var m = u64_shl(q, 9u);
    m.y = m.y | select(0u, 1u, !u64_is_zero(r));
    return f64_round(a.neg != b.neg, e, m);
}

// The f32 nearest to `a` (ties to even), as Rust's `a as f32` gives it: `finite` is false
// when it overflows to an infinity (then `bits` is that infinity).
struct F32Bits {
    finite: bool,
    bits: u32,
}

fn f64_to_f32(a: F64) -> F32Bits {
    let sign = select(0u, 0x80000000u, a.neg);
    if f64_is_zero(a) {
        return F32Bits(true, 0u);
    }
    if a.e > 127 {
        return F32Bits(false, sign | 0x7f800000u);
    }
    // Significand bits kept: 24 for a normal result, fewer for a subnormal one.
    var keep = 24;
    if a.e < -126 {
        keep = a.e + 150;
    }
    if keep <= 0 {
        // Below half the smallest subnormal (or exactly half: ties to even) rounds to zero.
        let above_half = keep == 0 && (a.m.x > 0x80000000u || a.m.y != 0u);
        return F32Bits(true, sign | select(0u, 1u, above_half));
    }
    // Dropping 40 to 63 bits: the kept ones all lie in the high word.
    let drop_hi = u32(64 - keep) - 32u;
    var q = a.m.x >> drop_hi;
    let rest_hi = a.m.x & ((1u << drop_hi) - 1u);
    let half_hi = 1u << (drop_hi - 1u);
    let above = rest_hi > half_hi || (rest_hi == half_hi && a.m.y != 0u);
    let tie = rest_hi == half_hi && a.m.y == 0u;
    if above || (tie && (q & 1u) != 0u) {
        q = q + 1u;
    }
    if keep < 24 {
        // A subnormal (or, rounded up to 2^23, the smallest normal: the same bits).
        return F32Bits(true, sign | q);
    }
    var e = a.e;
    if q == 0x1000000u {
        q = 0x800000u;
        e = e + 1;
    }
    if e > 127 {
        return F32Bits(false, sign | 0x7f800000u);
    }
    return F32Bits(true, sign | (u32(e + 127) << 23u) | (q & 0x7fffffu));
}

// a / b correctly rounded in f32, for b ≠ 0: the binary64 quotient rounded again to binary32.
// That second rounding never changes the result, because 53 ≥ 2 · 24 + 2 (Figueroa, "When is
// double rounding innocuous?", SIGNUM Newsletter 30(3), 1995). `finite` is false when the
// quotient overflows.
fn f32_div(a: f32, b: f32) -> F32Bits {
    return f64_to_f32(f64_div(f64_from_f32(a), f64_from_f32(b)));
}
