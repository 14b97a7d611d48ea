#version 450
// One pass of swell's Vulkan FFT (docs/vulkan.md): a batch of 1-D transforms of N points along
// "lines" of a 2-D array, each line held whole in shared memory, transformed there by Stockham
// autosort stages (Bainville's OpenCL FFT formulation: stage p reads x[i + j·N/R], writes
// x[(i − k)R + k + q·p], k = i mod p) of radix 8 after one first stage of radix 2, 4 or 8, and
// written back. Each thread holds 8·G points in registers per stage; two barriers a stage.
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
layout(constant_id = 4) const uint GROUPS = 1;      // groups of 8 points per thread
layout(constant_id = 5) const uint SHARED_POINTS = 64;  // N · LINES

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

// A thread's points during a stage (a private array, not a parameter: arrays passed inout
// were not copied back by lavapipe).
cplx x[8 * GROUPS];

// In-register DFTs of 2, 4 and 8 points at x[o …], in the pass's direction.
void dft2(uint o, uint s) {
  const cplx a = x[o], b = x[o + s];
  x[o] = a + b;
  x[o + s] = a - b;
}
void dft4(uint o, uint s) {  // x[o + q·s], q = 0 … 3
  const cplx t0 = x[o] + x[o + 2u * s], t1 = x[o] - x[o + 2u * s];
  const cplx t2 = x[o + s] + x[o + 3u * s], t3 = rotate(x[o + s] - x[o + 3u * s]);
  x[o] = t0 + t2;
  x[o + s] = t1 + t3;
  x[o + 2u * s] = t0 - t2;
  x[o + 3u * s] = t1 - t3;
}
void dft8(uint o) {
  // Decimation in time: E = DFT4(x0, x2, x4, x6), O = DFT4(x1, x3, x5, x7),
  // y_q = E_q + w8^q O_q, y_{q+4} = E_q − w8^q O_q.
  dft4(o, 2u);
  dft4(o + 1u, 2u);
  const cplx w1 = twiddle(N / 8u);  // e^(∓iπ/4), from the table like every other twiddle
  const cplx o1 = mul(x[o + 3u], w1);
  const cplx o2 = rotate(x[o + 5u]);
  const cplx o3 = rotate(mul(x[o + 7u], w1));
  const cplx e0 = x[o], e1 = x[o + 2u], e2 = x[o + 4u], e3 = x[o + 6u], o0 = x[o + 1u];
  x[o] = e0 + o0;      x[o + 4u] = e0 - o0;
  x[o + 1u] = e1 + o1; x[o + 5u] = e1 - o1;
  x[o + 2u] = e2 + o2; x[o + 6u] = e2 - o2;
  x[o + 3u] = e3 + o3; x[o + 7u] = e3 - o3;
}

// One Stockham stage of radix R with span p: every thread takes 8/R butterflies per group.
void stage(const uint R, const uint p) {
  const uint threads = gl_WorkGroupSize.x, t = gl_LocalInvocationID.x;
  const uint span = N / R;  // butterflies per line
  const uint per_group = 8u / R;
  for (uint g = 0u; g < GROUPS; ++g) {
    for (uint u = 0u; u < per_group; ++u) {
      const uint butterfly = (g * threads + t) * per_group + u;
      const uint l = butterfly / span, i = butterfly % span, k = i & (p - 1u);
      const uint o = g * 8u + u * R;
      for (uint j = 0u; j < R; ++j) {
        cplx v = line[l * N + i + j * span];
        if (j > 0u && p > 1u) v = mul(v, twiddle(j * k * (N / (p * R))));
        x[o + j] = v;
      }
      if (R == 2u) dft2(o, 1u);
      else if (R == 4u) dft4(o, 1u);
      else dft8(o);
    }
  }
  barrier();
  for (uint g = 0u; g < GROUPS; ++g) {
    for (uint u = 0u; u < per_group; ++u) {
      const uint butterfly = (g * threads + t) * per_group + u;
      const uint l = butterfly / span, i = butterfly % span, k = i & (p - 1u);
      const uint o = g * 8u + u * R;
      for (uint q = 0u; q < R; ++q) line[l * N + (i - k) * R + k + q * p] = x[o + q];
    }
  }
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
    stage(FIRST_RADIX, 1u);
    for (uint p = FIRST_RADIX; p < N; p *= 8u) stage(8u, p);
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
