#version 450
// One pass of swell's Vulkan FFT (docs/vulkan.md): a batch of 1-D transforms of N points along
// "lines" of a 2-D array, each line held whole in shared memory, transformed there by Stockham
// autosort stages (Bainville's OpenCL FFT formulation: stage p reads x[i + j·N/R], writes
// x[(i − k)R + k + q·p], k = i mod p) of radix 8 after one first stage of radix 2, 4 or 8; the
// first stage reads the array and the last writes it, so a line crosses shared memory once
// per stage boundary. Each thread holds 8 points in registers per stage; two barriers a stage.
//
// Addressing (push constants; strides in elements, complex or real): line (lo, hi) of batch b,
// element e lies at  b·batch + hi·hi_stride + lo·lo_stride + e·element_stride.  The x axis has
// element_stride 1 (or N2 in a two-pass split), the y axis lo_stride 1 with the columns of a
// workgroup adjacent, so a tile of columns is read row by row rather than transposed. On the x
// axis p = lo·lo_position + e·element_stride is the position in the row (lo_position is 0 where
// lo counts rows, lo_stride where it counts positions), which the real-data flags use:
//   REAL_INPUT     the source holds reals (r2c); imaginary parts are 0
//   HERMITIAN      the source holds the half row 0 … row/2 (c2r): p > row/2 reads conj(row − p)
//   REAL_OUTPUT    write the real part only (c2r)
//   LIMIT          write only p < limit (r2c keeps the half spectrum)
//   SPLIT_TWIDDLE  the first pass of a two-pass split N = N1·N2 multiplies output k1 of line n2
//                  by w_N^(n2·k1) (the four-step algorithm's twiddles), n2 = lo or hi
// Twiddles come from tables computed on the host in long double (drivers' sin and cos differ):
// line_twiddle[j] = e^(−2πij/N), split_twiddle[j] = e^(−2πij/N_total); inverse uses conj.
#ifdef SWELL_FP64
#define real double
#define cplx dvec2
#else
#define real float
#define cplx vec2
#endif

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint N = 64;          // points per line
layout(constant_id = 2) const uint LINES = 1;       // lines per workgroup
layout(constant_id = 3) const uint FIRST_RADIX = 8; // 1 (N = 1), 2, 4 or 8
layout(constant_id = 4) const uint SHARED_POINTS = 64;  // N · LINES

layout(set = 0, binding = 0) readonly buffer Source { real src[]; };
layout(set = 0, binding = 1) writeonly buffer Destination { real dst[]; };
layout(set = 0, binding = 2) readonly buffer LineTwiddles { cplx line_twiddle[]; };
layout(set = 0, binding = 3) readonly buffer SplitTwiddles { cplx split_twiddle[]; };

const uint INVERSE = 1u, REAL_INPUT = 2u, HERMITIAN = 4u, REAL_OUTPUT = 8u, LIMIT = 16u,
           SPLIT_TWIDDLE = 32u, SPLIT_BY_HI = 64u, SOURCE_LINE_FASTEST = 128u,
           DESTINATION_LINE_FASTEST = 256u;

// The pass's addressing and flags as specialization constants: every pass is its own
// pipeline, so the driver folds strides and flags into the code (as push constants they cost
// lavapipe a third of the time).
layout(constant_id = 5) const uint IN_LO = 0;
layout(constant_id = 6) const uint IN_LO_POSITION = 0;
layout(constant_id = 7) const uint IN_HI = 0;
layout(constant_id = 8) const uint IN_ELEMENT = 0;
layout(constant_id = 9) const uint IN_BATCH = 0;
layout(constant_id = 10) const uint OUT_LO = 0;
layout(constant_id = 11) const uint OUT_LO_POSITION = 0;
layout(constant_id = 12) const uint OUT_HI = 0;
layout(constant_id = 13) const uint OUT_ELEMENT = 0;
layout(constant_id = 14) const uint OUT_BATCH = 0;
layout(constant_id = 15) const uint LINES_LO = 1;
layout(constant_id = 16) const uint FLAGS = 0;
layout(constant_id = 17) const uint ROW = 0;
layout(constant_id = 18) const uint WRITE_LIMIT = 0;
layout(constant_id = 19) const uint SPLIT_N = 1;

shared cplx line[SHARED_POINTS];

bool has(uint flag) { return (FLAGS & flag) != 0u; }

cplx twiddle(uint j) {  // e^(∓2πij/N)
  cplx w = line_twiddle[j];
  return has(INVERSE) ? cplx(w.x, -w.y) : w;
}
cplx mul(cplx a, cplx b) { return cplx(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
// a · (∓i): forward multiplies by −i, inverse by +i.
cplx rotate(cplx a) { return has(INVERSE) ? cplx(-a.y, a.x) : cplx(a.y, -a.x); }

cplx load(uint b, uint hi, uint lo, uint e) {
  const uint p = lo * IN_LO_POSITION + e * IN_ELEMENT;  // in the row
  const uint base = b * IN_BATCH + hi * IN_HI + lo * IN_LO - lo * IN_LO_POSITION;
  if (has(REAL_INPUT)) return cplx(src[base + p], 0);
  if (has(HERMITIAN) && 2u * p > ROW) {
    const uint a = 2u * (base + ROW - p);
    return cplx(src[a], -src[a + 1u]);
  }
  const uint a = 2u * (base + p);
  return cplx(src[a], src[a + 1u]);
}

void store(uint b, uint hi, uint lo, uint e, cplx v) {
  const uint p = lo * OUT_LO_POSITION + e * OUT_ELEMENT;  // in the row
  const uint base = b * OUT_BATCH + hi * OUT_HI + lo * OUT_LO - lo * OUT_LO_POSITION;
  if (has(LIMIT) && p >= WRITE_LIMIT) return;
  if (has(REAL_OUTPUT)) {
    dst[base + p] = v.x;
    return;
  }
  const uint a = 2u * (base + p);
  dst[a] = v.x;
  dst[a + 1u] = v.y;
}

// In-register DFTs of 2, 4 and 8 points in the pass's direction, on named values rather than
// arrays: lavapipe runs the invocations of a workgroup as SIMD lanes, and a private array
// indexed in a loop became memory (5× slower than VkFFT's unrolled kernels).
void dft2(inout cplx a, inout cplx b) {
  const cplx t = a - b;
  a = a + b;
  b = t;
}
void dft4(inout cplx x0, inout cplx x1, inout cplx x2, inout cplx x3) {
  const cplx t0 = x0 + x2, t1 = x0 - x2, t2 = x1 + x3, t3 = rotate(x1 - x3);
  x0 = t0 + t2;
  x1 = t1 + t3;
  x2 = t0 - t2;
  x3 = t1 - t3;
}
void dft8(inout cplx x0, inout cplx x1, inout cplx x2, inout cplx x3, inout cplx x4,
          inout cplx x5, inout cplx x6, inout cplx x7) {
  // Decimation in time: E = DFT4(x0, x2, x4, x6), O = DFT4(x1, x3, x5, x7),
  // y_q = E_q + w8^q O_q, y_{q+4} = E_q − w8^q O_q, w8 = e^(∓iπ/4) from the table like every
  // other twiddle.
  dft4(x0, x2, x4, x6);
  dft4(x1, x3, x5, x7);
  const cplx w1 = twiddle(N / 8u);
  const cplx o1 = mul(x3, w1), o2 = rotate(x5), o3 = rotate(mul(x7, w1));
  const cplx e0 = x0, e1 = x2, e2 = x4, e3 = x6, o0 = x1;
  x0 = e0 + o0; x4 = e0 - o0;
  x1 = e1 + o1; x5 = e1 - o1;
  x2 = e2 + o2; x6 = e2 - o2;
  x3 = e3 + o3; x7 = e3 - o3;
}

// Every thread holds 8 points of a stage: one radix-8 butterfly, two radix-4 or four radix-2.
cplx v0, v1, v2, v3, v4, v5, v6, v7;

// Which line of the workgroup and which butterfly of that line butterfly b is: lines fastest
// where the array's lines are adjacent in memory (the y axis's columns), so that neighbouring
// invocations touch neighbouring addresses when a stage reads or writes the array itself.
uvec2 line_and_index(uint b, uint per_line, bool lines_fastest) {
  return lines_fastest ? uvec2(b % LINES, b / LINES) : uvec2(b / per_line, b % per_line);
}

cplx fetch(uint l, uint e) {
  const uint lo = gl_WorkGroupID.x * LINES + l;
  return lo < LINES_LO ? load(gl_WorkGroupID.z, gl_WorkGroupID.y, lo, e) : cplx(0);
}

void put(uint l, uint e, cplx v) {
  const uint lo = gl_WorkGroupID.x * LINES + l;
  if (lo >= LINES_LO) return;
  if (has(SPLIT_TWIDDLE)) {
    const uint n2 = has(SPLIT_BY_HI) ? gl_WorkGroupID.y : lo;
    const cplx w = split_twiddle[(n2 * e) % SPLIT_N];
    v = mul(v, has(INVERSE) ? cplx(w.x, -w.y) : w);
  }
  store(gl_WorkGroupID.z, gl_WorkGroupID.y, lo, e, v);
}

// The first stage (span 1, no twiddles) of radix FIRST_RADIX, read from the array itself:
// butterfly i of a line reads x[i + j·N/R] and writes x[i·R + q] — to shared memory, or, when
// it is the only stage (N = R), to the array.
void first_stage() {
  const uint t = gl_LocalInvocationID.x;
  const bool last = FIRST_RADIX == N;
  const bool in_fastest = has(SOURCE_LINE_FASTEST), out_fastest = has(DESTINATION_LINE_FASTEST);
  const uint step = N / FIRST_RADIX;
  if (FIRST_RADIX == 8u) {
    const uvec2 li = line_and_index(t, step, last ? out_fastest : in_fastest);
    const uint l = li.x, i = li.y;
    v0 = fetch(l, i); v1 = fetch(l, i + step); v2 = fetch(l, i + 2u * step); v3 = fetch(l, i + 3u * step);
    v4 = fetch(l, i + 4u * step); v5 = fetch(l, i + 5u * step); v6 = fetch(l, i + 6u * step); v7 = fetch(l, i + 7u * step);
    dft8(v0, v1, v2, v3, v4, v5, v6, v7);
    if (last) {
      put(l, 0u, v0); put(l, 1u, v1); put(l, 2u, v2); put(l, 3u, v3);
      put(l, 4u, v4); put(l, 5u, v5); put(l, 6u, v6); put(l, 7u, v7);
      return;
    }
    const uint to = l * N + i * 8u;
    line[to] = v0; line[to + 1u] = v1; line[to + 2u] = v2; line[to + 3u] = v3;
    line[to + 4u] = v4; line[to + 5u] = v5; line[to + 6u] = v6; line[to + 7u] = v7;
  } else if (FIRST_RADIX == 4u) {
    const uvec2 a = line_and_index(2u * t, step, last ? out_fastest : in_fastest);
    const uvec2 b = line_and_index(2u * t + 1u, step, last ? out_fastest : in_fastest);
    v0 = fetch(a.x, a.y); v1 = fetch(a.x, a.y + step); v2 = fetch(a.x, a.y + 2u * step); v3 = fetch(a.x, a.y + 3u * step);
    v4 = fetch(b.x, b.y); v5 = fetch(b.x, b.y + step); v6 = fetch(b.x, b.y + 2u * step); v7 = fetch(b.x, b.y + 3u * step);
    dft4(v0, v1, v2, v3);
    dft4(v4, v5, v6, v7);
    if (last) {
      put(a.x, 0u, v0); put(a.x, 1u, v1); put(a.x, 2u, v2); put(a.x, 3u, v3);
      put(b.x, 0u, v4); put(b.x, 1u, v5); put(b.x, 2u, v6); put(b.x, 3u, v7);
      return;
    }
    const uint ta = a.x * N + a.y * 4u, tb = b.x * N + b.y * 4u;
    line[ta] = v0; line[ta + 1u] = v1; line[ta + 2u] = v2; line[ta + 3u] = v3;
    line[tb] = v4; line[tb + 1u] = v5; line[tb + 2u] = v6; line[tb + 3u] = v7;
  } else {
    const bool fastest = last ? out_fastest : in_fastest;
    const uvec2 a = line_and_index(4u * t, step, fastest), b = line_and_index(4u * t + 1u, step, fastest);
    const uvec2 c = line_and_index(4u * t + 2u, step, fastest), d = line_and_index(4u * t + 3u, step, fastest);
    v0 = fetch(a.x, a.y); v1 = fetch(a.x, a.y + step); v2 = fetch(b.x, b.y); v3 = fetch(b.x, b.y + step);
    v4 = fetch(c.x, c.y); v5 = fetch(c.x, c.y + step); v6 = fetch(d.x, d.y); v7 = fetch(d.x, d.y + step);
    dft2(v0, v1); dft2(v2, v3); dft2(v4, v5); dft2(v6, v7);
    if (last) {
      put(a.x, 0u, v0); put(a.x, 1u, v1); put(b.x, 0u, v2); put(b.x, 1u, v3);
      put(c.x, 0u, v4); put(c.x, 1u, v5); put(d.x, 0u, v6); put(d.x, 1u, v7);
      return;
    }
    line[a.x * N + a.y * 2u] = v0; line[a.x * N + a.y * 2u + 1u] = v1;
    line[b.x * N + b.y * 2u] = v2; line[b.x * N + b.y * 2u + 1u] = v3;
    line[c.x * N + c.y * 2u] = v4; line[c.x * N + c.y * 2u + 1u] = v5;
    line[d.x * N + d.y * 2u] = v6; line[d.x * N + d.y * 2u + 1u] = v7;
  }
  barrier();
}

// A radix-8 Stockham stage of span p > 1: butterfly i (k = i mod p) reads x[i + j·N/8] times
// w_{8p}^(jk) and writes x[(i − k)·8 + k + q·p] — the last stage (8p = N, so k = i) straight to
// the array's element i + q·N/8.
void radix8_stage(const uint p) {
  const uint t = gl_LocalInvocationID.x;
  const bool last = 8u * p == N;
  const uint step = N / 8u;
  const uvec2 li = line_and_index(t, step, last && has(DESTINATION_LINE_FASTEST));
  const uint l = li.x, i = li.y, k = i & (p - 1u), at = l * N + i;
  const uint w = k * (N / (8u * p));  // twiddle index of j = 1
  v0 = line[at];
  v1 = mul(line[at + step], twiddle(w));
  v2 = mul(line[at + 2u * step], twiddle(2u * w));
  v3 = mul(line[at + 3u * step], twiddle(3u * w));
  v4 = mul(line[at + 4u * step], twiddle(4u * w));
  v5 = mul(line[at + 5u * step], twiddle(5u * w));
  v6 = mul(line[at + 6u * step], twiddle(6u * w));
  v7 = mul(line[at + 7u * step], twiddle(7u * w));
  dft8(v0, v1, v2, v3, v4, v5, v6, v7);
  if (last) {
    put(l, i, v0); put(l, i + step, v1); put(l, i + 2u * step, v2); put(l, i + 3u * step, v3);
    put(l, i + 4u * step, v4); put(l, i + 5u * step, v5); put(l, i + 6u * step, v6); put(l, i + 7u * step, v7);
    return;
  }
  barrier();
  const uint to = l * N + (i - k) * 8u + k;
  line[to] = v0; line[to + p] = v1; line[to + 2u * p] = v2; line[to + 3u * p] = v3;
  line[to + 4u * p] = v4; line[to + 5u * p] = v5; line[to + 6u * p] = v6; line[to + 7u * p] = v7;
  barrier();
}

void main() {
  if (FIRST_RADIX == 1u) {  // N = 1: a copy (with the flags' conversions)
    const uint t = gl_LocalInvocationID.x;
    for (uint l = t; l < LINES; l += gl_WorkGroupSize.x) put(l, 0u, fetch(l, 0u));
    return;
  }
  first_stage();
  for (uint p = FIRST_RADIX; p < N; p *= 8u) radix8_stage(p);
}
