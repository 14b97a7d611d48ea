#version 450
// One pass of swell's Vulkan FFT (docs/vulkan.md): a batch of 1-D transforms of N points along
// "lines" of a 2-D array, each line held whole in shared memory, transformed there by Stockham
// autosort stages (Bainville's OpenCL FFT formulation: stage p reads x[i + j·N/R], writes
// x[(i − k)R + k + q·p], k = i mod p) of radix 8 after one first stage of radix 2, 4 or 8, and
// written back. Each thread holds 8 points in registers per stage; two barriers a stage.
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

layout(push_constant) uniform Pass {
  uint in_lo, in_lo_position, in_hi, in_element, in_batch;
  uint out_lo, out_lo_position, out_hi, out_element, out_batch;
  uint lines_lo;     // lines along lo (a workgroup takes LINES adjacent ones; the last may be short)
  uint flags;
  uint row;          // the x axis's full length (REAL_INPUT, HERMITIAN)
  uint limit;        // LIMIT: positions written
  uint split_n;      // SPLIT_TWIDDLE: N_total
} pass;

shared cplx line[SHARED_POINTS];

bool has(uint flag) { return (pass.flags & flag) != 0u; }

cplx twiddle(uint j) {  // e^(∓2πij/N)
  cplx w = line_twiddle[j];
  return has(INVERSE) ? cplx(w.x, -w.y) : w;
}
cplx mul(cplx a, cplx b) { return cplx(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
// a · (∓i): forward multiplies by −i, inverse by +i.
cplx rotate(cplx a) { return has(INVERSE) ? cplx(-a.y, a.x) : cplx(a.y, -a.x); }

cplx load(uint b, uint hi, uint lo, uint e) {
  const uint p = lo * pass.in_lo_position + e * pass.in_element;  // in the row
  const uint base = b * pass.in_batch + hi * pass.in_hi + lo * pass.in_lo - lo * pass.in_lo_position;
  if (has(REAL_INPUT)) return cplx(src[base + p], 0);
  if (has(HERMITIAN) && 2u * p > pass.row) {
    const uint a = 2u * (base + pass.row - p);
    return cplx(src[a], -src[a + 1u]);
  }
  const uint a = 2u * (base + p);
  return cplx(src[a], src[a + 1u]);
}

void store(uint b, uint hi, uint lo, uint e, cplx v) {
  const uint p = lo * pass.out_lo_position + e * pass.out_element;  // in the row
  const uint base = b * pass.out_batch + hi * pass.out_hi + lo * pass.out_lo - lo * pass.out_lo_position;
  if (has(LIMIT) && p >= pass.limit) return;
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

// The first stage (span 1, no twiddles) of radix FIRST_RADIX: butterfly i of a line reads
// x[i + j·N/R] and writes x[i·R + q].
void first_stage() {
  const uint t = gl_LocalInvocationID.x;
  if (FIRST_RADIX == 8u) {
    const uint l = t / (N / 8u), i = t % (N / 8u), at = l * N + i, step = N / 8u;
    v0 = line[at]; v1 = line[at + step]; v2 = line[at + 2u * step]; v3 = line[at + 3u * step];
    v4 = line[at + 4u * step]; v5 = line[at + 5u * step]; v6 = line[at + 6u * step]; v7 = line[at + 7u * step];
    dft8(v0, v1, v2, v3, v4, v5, v6, v7);
    barrier();
    const uint to = l * N + i * 8u;
    line[to] = v0; line[to + 1u] = v1; line[to + 2u] = v2; line[to + 3u] = v3;
    line[to + 4u] = v4; line[to + 5u] = v5; line[to + 6u] = v6; line[to + 7u] = v7;
  } else if (FIRST_RADIX == 4u) {
    const uint b0 = 2u * t, b1 = b0 + 1u, step = N / 4u;
    const uint a0 = (b0 / step) * N + b0 % step, a1 = (b1 / step) * N + b1 % step;
    v0 = line[a0]; v1 = line[a0 + step]; v2 = line[a0 + 2u * step]; v3 = line[a0 + 3u * step];
    v4 = line[a1]; v5 = line[a1 + step]; v6 = line[a1 + 2u * step]; v7 = line[a1 + 3u * step];
    dft4(v0, v1, v2, v3);
    dft4(v4, v5, v6, v7);
    barrier();
    const uint t0 = (b0 / step) * N + (b0 % step) * 4u, t1 = (b1 / step) * N + (b1 % step) * 4u;
    line[t0] = v0; line[t0 + 1u] = v1; line[t0 + 2u] = v2; line[t0 + 3u] = v3;
    line[t1] = v4; line[t1 + 1u] = v5; line[t1 + 2u] = v6; line[t1 + 3u] = v7;
  } else {
    const uint step = N / 2u;
    uint a[4], to[4];
    for (uint u = 0u; u < 4u; ++u) {
      const uint b = 4u * t + u;
      a[u] = (b / step) * N + b % step;
      to[u] = (b / step) * N + (b % step) * 2u;
    }
    v0 = line[a[0]]; v1 = line[a[0] + step]; v2 = line[a[1]]; v3 = line[a[1] + step];
    v4 = line[a[2]]; v5 = line[a[2] + step]; v6 = line[a[3]]; v7 = line[a[3] + step];
    dft2(v0, v1); dft2(v2, v3); dft2(v4, v5); dft2(v6, v7);
    barrier();
    line[to[0]] = v0; line[to[0] + 1u] = v1; line[to[1]] = v2; line[to[1] + 1u] = v3;
    line[to[2]] = v4; line[to[2] + 1u] = v5; line[to[3]] = v6; line[to[3] + 1u] = v7;
  }
  barrier();
}

// A radix-8 Stockham stage of span p > 1: butterfly i (k = i mod p) reads x[i + j·N/8] times
// w_{8p}^(jk) and writes x[(i − k)·8 + k + q·p].
void radix8_stage(const uint p) {
  const uint t = gl_LocalInvocationID.x;
  const uint step = N / 8u, l = t / step, i = t % step, k = i & (p - 1u), at = l * N + i;
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
  barrier();
  const uint to = l * N + (i - k) * 8u + k;
  line[to] = v0; line[to + p] = v1; line[to + 2u * p] = v2; line[to + 3u * p] = v3;
  line[to + 4u * p] = v4; line[to + 5u * p] = v5; line[to + 6u * p] = v6; line[to + 7u * p] = v7;
  barrier();
}

void main() {
  const uint threads = gl_WorkGroupSize.x, t = gl_LocalInvocationID.x;
  const uint lo0 = gl_WorkGroupID.x * LINES, hi = gl_WorkGroupID.y, b = gl_WorkGroupID.z;
  const uint points = N * LINES;
  for (uint index = t; index < points; index += threads) {
    uint l, e;
    if (has(SOURCE_LINE_FASTEST)) { l = index % LINES; e = index / LINES; }
    else { e = index % N; l = index / N; }
    line[l * N + e] = lo0 + l < pass.lines_lo ? load(b, hi, lo0 + l, e) : cplx(0);
  }
  barrier();
  if (FIRST_RADIX > 1u) {
    first_stage();
    for (uint p = FIRST_RADIX; p < N; p *= 8u) radix8_stage(p);
  }
  for (uint index = t; index < points; index += threads) {
    uint l, e;
    if (has(DESTINATION_LINE_FASTEST)) { l = index % LINES; e = index / LINES; }
    else { e = index % N; l = index / N; }
    if (lo0 + l >= pass.lines_lo) continue;
    cplx v = line[l * N + e];
    if (has(SPLIT_TWIDDLE)) {
      const uint n2 = has(SPLIT_BY_HI) ? hi : lo0 + l;
      cplx w = split_twiddle[(n2 * e) % pass.split_n];
      v = mul(v, has(INVERSE) ? cplx(w.x, -w.y) : w);
    }
    store(b, hi, lo0 + l, e, v);
  }
}
