#version 450
#ifdef SWELL_SHUFFLE
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_shuffle : require
#endif
// One pass of swell's Vulkan FFT (docs/vulkan.md): a batch of 1-D transforms of N points along
// "lines" of a 2-D array, each line held whole in shared memory, transformed there by Stockham
// autosort stages (Bainville's OpenCL FFT formulation: stage p reads x[i + j·N/R], writes
// x[(i − k)R + k + q·p], k = i mod p): a first stage of radix 2 (N = 2 only), 4, 8 or 16, at
// most one radix-8 stage, then radix-16 ones; the first stage reads the array and the last
// writes it, so a line crosses shared memory once per stage boundary. Each thread holds 16
// points in registers per stage; one barrier a stage with two copies in shared memory, else two.
//
// Addressing (specialization constants; strides in elements, complex or real): line (lo, hi) of batch b,
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
//
// Built with -DSWELL_FRAME (fft_frame_*), the first pass of the synthesizer's frame makes the
// packed spectra it reads and the last pass writes the six fields (FRAME_SOURCE, FRAME_FIELDS;
// see the SWELL_FRAME section below and docs/synthesis.md §vulkan).
#ifdef SWELL_FP64
#define real double
#define cplx dvec2
#define vec4_or_dvec4 dvec4
#else
#define real float
#define cplx vec2
#define vec4_or_dvec4 vec4
#endif

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const uint N = 64;          // points per line
layout(constant_id = 2) const uint LINES = 1;       // lines per workgroup
layout(constant_id = 3) const uint FIRST_RADIX = 16; // 1 (N = 1), 2, 4, 8 or 16
layout(constant_id = 4) const uint SHARED_POINTS = 64;  // N · LINES

// Each array is bound once and read as complex numbers or (real data) as reals.
layout(set = 0, binding = 0) readonly buffer Source { cplx src[]; };
layout(set = 0, binding = 0) readonly buffer RealSource { real src_real[]; };
layout(set = 0, binding = 1) writeonly buffer Destination { cplx dst[]; };
layout(set = 0, binding = 1) writeonly buffer RealDestination { real dst_real[]; };
layout(set = 0, binding = 2) readonly buffer LineTwiddles { cplx line_twiddle[]; };
layout(set = 0, binding = 3) readonly buffer SplitTwiddles { cplx split_twiddle[]; };

const uint INVERSE = 1u, REAL_INPUT = 2u, HERMITIAN = 4u, REAL_OUTPUT = 8u, LIMIT = 16u,
           SPLIT_TWIDDLE = 32u, SPLIT_BY_HI = 64u, SOURCE_LINE_FASTEST = 128u,
           DESTINATION_LINE_FASTEST = 256u, FRAME_SOURCE = 512u, FRAME_FIELDS = 1024u,
           FRAME_JACOBIAN = 2048u;

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

// Two copies of the lines where shared memory allows (PING_PONG = 1): a stage reads one and
// writes the other, one barrier a stage and no registers held across it (lavapipe saves them
// at every barrier); else one copy, read, barrier, write, barrier.
layout(constant_id = 20) const uint PING_PONG = 0;
layout(constant_id = 21) const uint RADIX8_STAGES = 0;  // after the first stage, before the radix-16 ones
shared cplx line[SHARED_POINTS * (1u + PING_PONG)];
uint current = 0u;  // offset of the copy the next stage reads; writes go to the other

// After a stage's writes: the copy just written is the one the next stage reads.
void swap_copies() {
  if (PING_PONG == 1u) current = SHARED_POINTS - current;
}

bool has(uint flag) { return (FLAGS & flag) != 0u; }

// The workgroup's place: its lines along x and its transform of the batch. A pass may
// interleave the batch along x (BATCH_IN_X transforms: workgroup x holds lines x / BATCH_IN_X
// of transform x mod BATCH_IN_X), so that the workgroups of one set of lines in every
// transform run one after the other.
layout(constant_id = 25) const uint BATCH_IN_X = 1;
uint group_x() { return gl_WorkGroupID.x / BATCH_IN_X; }
uint group_batch() { return gl_WorkGroupID.x % BATCH_IN_X + gl_WorkGroupID.z; }

// A pass over adjacent lines (the y axis's columns, or the first pass of an x-axis split): the
// invocations of a SIMD group take neighbouring lines in every stage and shared memory holds
// element e of line l at e·LINES + l, so that a stage's loads and stores are contiguous across
// lanes rather than N apart (the layout a GPU's shared-memory banks want). On lavapipe, whose
// shared-memory accesses go lane by lane anyway, it measured the same as l·N + e.
bool columns_pass() { return has(SOURCE_LINE_FASTEST) && has(DESTINATION_LINE_FASTEST); }
uint shared_index(uint l, uint e) { return columns_pass() ? e * LINES + l : l * N + e; }
uint element_pitch() { return columns_pass() ? LINES : 1u; }

cplx twiddle(uint j) {  // e^(∓2πij/N)
  cplx w = line_twiddle[j];
  return has(INVERSE) ? cplx(w.x, -w.y) : w;
}
cplx mul(cplx a, cplx b) { return cplx(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }
// a · (∓i): forward multiplies by −i, inverse by +i.
cplx rotate(cplx a) { return has(INVERSE) ? cplx(-a.y, a.x) : cplx(a.y, -a.x); }

#ifdef SWELL_FRAME
// ------------------------------------------------------------------ the synthesizer's frame
// The frame program (impls/src/vulkan/frame.cpp) is the synthesizer's batch of inverse
// transforms — PAIRS: four c2c of nx × ny, the real fields (h, ∂h/∂x), (∂h/∂y, λDx),
// (λDy, λ∂Dx/∂x), (λ∂Dy/∂y, λ∂Dx/∂y) packed as A + iB; else eight c2r, one real field each, in
// that order — whose first pass reads spectra nobody stored and whose last pass writes the
// fields nobody has to unpack. On lavapipe every storage-buffer access is a loop over the SIMD
// lanes (docs/vulkan.md §Kernels): a kernel that wrote the packed spectra and one that read the
// transforms back to make the fields cost 1.4–1.8× the transforms. Fused, the first pass reads
// one value a point as the bare pass does, and the last writes one a point as it does.
//
// FRAME_SOURCE (the first pass): element a of the (virtual) batch of spectra, C = nx (PAIRS) or
// nx/2 + 1 (c2r) columns by ny rows a plane, is m·h̃(k, t), h̃ from the evolution kernel's half
// spectrum (frame_evolve.comp; columns 0 … nx/2, row-major) — for columns beyond nx/2, conj(h̃)
// of the mirror entry (−k; h̃(−k) = conj(h̃(k))) — and m the plane's multiplier: for one real
// field r, c_r = 1, i kx, i ky, iλkx/k, iλky/k, −λkx²/k, −λky²/k, −λkxky/k (docs/conventions.md
// §Derived fields) times its scale (a power of two that keeps fp32 in range; synthesizer.cpp's
// State::field_scale); for a pair, c_A + i c_B, whose inverse transform is a + ib. kx and ky are
// the signed index times Δk in double, rounded once, as the host's tables hold them; λ/|k| is
// computed in the synthesis precision (the host's table rounds it once from double: they
// differ by an ulp or two, far inside the fp32 bound; reading it beside h̃ cost a second word a
// point).
//
// FRAME_FIELDS (the last pass): each value goes where the bare pass would store it, times the
// inverse scales (0 for a field that is zero by definition), so the fields lie in the pass's
// destination. PAIRS (in place over the packed spectra): planes 0, 1, 2 hold (h, ∂h/∂x),
// (∂h/∂y, λDx), (λDy, λ∂Dx/∂x); then the last plane's pipeline (FRAME_JACOBIAN), dispatched
// after the others behind a barrier, reads plane 2, makes J = (1 + λ∂Dx/∂x)(1 + λ∂Dy/∂y) −
// (λ∂Dx/∂y)² from it and its own values, and writes (λDy, J) over it (plane 2's workgroups
// going on to plane 3 instead, J from values still in their cache, measured 3–7 % slower on
// lavapipe, side by side); the host's copy of the
// frame splits the three pairs into the six fields. c2r: plane r holds field r (λ∂Dx/∂x in
// plane 5, λ∂Dy/∂y in plane 6), and the last plane's pipeline reads planes 5 and 6 and writes J
// over plane 5. The J pipeline's planes start at plane JACOBIAN_FIRST of the destination
// binding (0, or, dispatched one transform at a time, the first plane it reads). A non-finite
// field value is counted into `non_finite` (the synthesizer then throws an InternalError
// naming it, never returning a frame with infinities); the test is on the exponent bits, which
// no assumption about NaN (fast math) can fold away, as isnan could be.
//
// The plane is the workgroup's transform of the batch (group_batch(); with a batch beyond one
// binding, dispatched one transform at a time, the dispatch's base workgroup z); IN_BATCH is
// the virtual spectra's plane size, so b·IN_BATCH + the offset in the plane names an element.
layout(constant_id = 22) const uint FRAME_NY = 1;         // rows of a plane
layout(constant_id = 23) const bool PAIRS = true;
layout(constant_id = 24) const uint JACOBIAN_FIRST = 0;

#ifdef SWELL_FP64
layout(set = 0, binding = 0) readonly buffer Table { dvec2 table[]; };  // h̃
layout(set = 0, binding = 5, std140) uniform FrameConstants {
  dvec4 field_scale_0123, field_scale_4567, inverse_scale[2];
  double dkx, dky;   // rad/m
  double lambda;     // the choppiness λ
} frame;
#else
// h̃ as one 64-bit word (an fp32 complex, real part in the low half: one memory access, not two).
layout(set = 0, binding = 0) readonly buffer Table { double table[]; };
layout(set = 0, binding = 5, std140) uniform FrameConstants {
  vec4 field_scale_0123, field_scale_4567, inverse_scale[2];
  double dkx, dky;   // rad/m
  double lambda;     // the choppiness λ
} frame;
#endif
// The J pipeline reads the planes it makes J from through the destination binding.
layout(set = 0, binding = 1) readonly buffer DestinationRead { cplx dst_read[]; };
layout(set = 0, binding = 1) readonly buffer RealDestinationRead { real dst_real_read[]; };
layout(set = 0, binding = 4) buffer Probe { uint non_finite; };

uint frame_non_finite = 0u;  // this invocation's count, added to the probe once at the end

// Grid::signed_index, and kx of column i (ky of row j) as the host's tables hold it.
int signed_index(uint i, uint n) { return i < (n + 1u) / 2u ? int(i) : int(i) - int(n); }
real wave_number(uint i, uint n, double dk) { return real(double(signed_index(i, n)) * dk); }

// m of plane `plane` at (kx, ky) with lk = λ/|k| (see above), s = the field scales.
cplx multiplier(uint plane, real kx, real ky, real lk, vec4_or_dvec4 s0123, vec4_or_dvec4 s4567) {
  if (PAIRS) {
    switch (plane) {
      case 0u: return cplx(s0123.x - kx * s0123.y, 0);                        // h + i ∂h/∂x
      case 1u: return cplx(-lk * kx * s0123.w, ky * s0123.z);                 // ∂h/∂y + i λDx
      case 2u: return cplx(0, lk * ky * s4567.x - lk * kx * kx * s4567.y);    // λDy + i λ∂Dx/∂x
      default: return cplx(-lk * ky * ky * s4567.z, -lk * kx * ky * s4567.w); // λ∂Dy/∂y + i λ∂Dx/∂y
    }
  }
  switch (plane) {
    case 0u: return cplx(s0123.x, 0);
    case 1u: return cplx(0, kx * s0123.y);
    case 2u: return cplx(0, ky * s0123.z);
    case 3u: return cplx(0, lk * kx * s0123.w);
    case 4u: return cplx(0, lk * ky * s4567.x);
    case 5u: return cplx(-lk * kx * kx * s4567.y, 0);
    case 6u: return cplx(-lk * ky * ky * s4567.z, 0);
    default: return cplx(-lk * kx * ky * s4567.w, 0);
  }
}

cplx frame_spectrum(uint a) {
  const uint columns = PAIRS ? ROW : ROW / 2u + 1u;
  const uint plane = group_batch(), o = a - plane * IN_BATCH, j = o / columns, i = o % columns;
  // Columns beyond nx/2 (PAIRS) hold −k of the half spectrum's column nx − i, row (ny − j) mod ny.
  const bool mirrored = i > ROW / 2u;
  const uint entry = mirrored ? ((FRAME_NY - j) % FRAME_NY) * (ROW / 2u + 1u) + (ROW - i)
                              : j * (ROW / 2u + 1u) + i;
#ifdef SWELL_FP64
  const cplx h = table[entry];
#else
  const cplx h = uintBitsToFloat(unpackDouble2x32(table[entry]));
#endif
  const real kx = wave_number(i, ROW, frame.dkx), ky = wave_number(j, FRAME_NY, frame.dky);
  const real k2 = kx * kx + ky * ky;
  const real lk = k2 > 0.0 ? real(frame.lambda) / sqrt(k2) : real(0);  // k = 0 carries no wave
  const cplx m = multiplier(plane, kx, ky, lk, frame.field_scale_0123, frame.field_scale_4567);
  return mul(m, cplx(h.x, mirrored ? -h.y : h.y));
}

bool finite(float v) { return (floatBitsToUint(v) & 0x7f800000u) != 0x7f800000u; }
bool finite(double v) { return (unpackDouble2x32(v).y & 0x7ff00000u) != 0x7ff00000u; }
uint non_finite_count(real v) { return finite(v) ? 0u : 1u; }

real inverse_scale(uint r) { return frame.inverse_scale[r / 4u][r % 4u]; }

// The value v of element `at` of the destination binding, in plane p = the workgroup's, to the
// fields (see above). Straight-line code: on lavapipe both arms of a branch run, with masks.
void frame_fields(uint at, cplx v) {
  const uint plane = group_batch(), samples = ROW * FRAME_NY;
  if (has(FRAME_JACOBIAN)) {
    const uint s = at - plane * OUT_BATCH;  // the sample
    if (PAIRS) {
      const uint first_input = (plane - 1u - JACOBIAN_FIRST) * samples + s;
      const cplx dy_dxx = dst_read[first_input];
      const real dxx = dy_dxx.y, dyy = v.x * inverse_scale(6u), dxy = v.y * inverse_scale(7u);
      const real jacobian = (1.0 + dxx) * (1.0 + dyy) - dxy * dxy;
      dst[first_input] = cplx(dy_dxx.x, jacobian);
      frame_non_finite += non_finite_count(jacobian);
    } else {
      const uint first_input = (plane - 2u - JACOBIAN_FIRST) * samples + s;
      const real dxx = dst_real_read[first_input], dyy = dst_real_read[first_input + samples];
      const real dxy = v.x * inverse_scale(7u);
      const real jacobian = (1.0 + dxx) * (1.0 + dyy) - dxy * dxy;
      dst_real[first_input] = jacobian;
      frame_non_finite += non_finite_count(jacobian);
    }
    return;
  }
  if (PAIRS) {
    const real first = v.x * inverse_scale(2u * plane), second = v.y * inverse_scale(2u * plane + 1u);
    dst[at] = cplx(first, second);
    frame_non_finite += non_finite_count(first) + (plane < 2u ? non_finite_count(second) : 0u);
  } else {
    const real value = v.x * inverse_scale(plane);
    dst_real[at] = value;
    frame_non_finite += plane < 5u ? non_finite_count(value) : 0u;
  }
}

// After the last store: this invocation's non-finite values into the probe.
void frame_finish() {
  if (has(FRAME_FIELDS) && frame_non_finite != 0u) atomicAdd(non_finite, frame_non_finite);
}

cplx read_source(uint a) { return has(FRAME_SOURCE) ? frame_spectrum(a) : src[a]; }
#else
cplx read_source(uint a) { return src[a]; }
void frame_finish() {}
#endif

cplx load(uint b, uint hi, uint lo, uint e) {
  const uint p = lo * IN_LO_POSITION + e * IN_ELEMENT;  // in the row
  const uint base = b * IN_BATCH + hi * IN_HI + lo * IN_LO - lo * IN_LO_POSITION;
  if (has(REAL_INPUT)) return cplx(src_real[base + p], 0);
  if (has(HERMITIAN) && 2u * p > ROW) {
    const cplx mirror = read_source(base + ROW - p);
    return cplx(mirror.x, -mirror.y);
  }
  return read_source(base + p);
}

void store(uint b, uint hi, uint lo, uint e, cplx v) {
  const uint p = lo * OUT_LO_POSITION + e * OUT_ELEMENT;  // in the row
  const uint base = b * OUT_BATCH + hi * OUT_HI + lo * OUT_LO - lo * OUT_LO_POSITION;
  if (has(LIMIT) && p >= WRITE_LIMIT) return;
#ifdef SWELL_FRAME
  if (has(FRAME_FIELDS)) {
    frame_fields(base + p, v);
    return;
  }
#endif
  if (has(REAL_OUTPUT)) {
    dst_real[base + p] = v.x;
    return;
  }
  dst[base + p] = v;
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

// dft16 as 4 × 4 (n = 4 n1 + n2, k = k1 + 4 k2): DFT4 over n1, twiddles w16^(n2 k1), DFT4
// over n2. X[k] ends in x_{4 (k mod 4) + k div 4}; the stages read it back in that order.
void dft16(inout cplx x0, inout cplx x1, inout cplx x2, inout cplx x3, inout cplx x4,
           inout cplx x5, inout cplx x6, inout cplx x7, inout cplx x8, inout cplx x9,
           inout cplx x10, inout cplx x11, inout cplx x12, inout cplx x13, inout cplx x14,
           inout cplx x15) {
  dft4(x0, x4, x8, x12);
  dft4(x1, x5, x9, x13);
  dft4(x2, x6, x10, x14);
  dft4(x3, x7, x11, x15);
  const uint s = N / 16u;  // w16^m = twiddle(m·N/16)
  const cplx w1 = twiddle(s), w2 = twiddle(2u * s), w3 = twiddle(3u * s);
  const cplx w6 = twiddle(6u * s), w9 = twiddle(9u * s);
  x5 = mul(x5, w1); x6 = mul(x6, w2); x7 = mul(x7, w3);
  x9 = mul(x9, w2); x10 = rotate(x10); x11 = mul(x11, w6);
  x13 = mul(x13, w3); x14 = mul(x14, w6); x15 = mul(x15, w9);
  dft4(x0, x1, x2, x3);
  dft4(x4, x5, x6, x7);
  dft4(x8, x9, x10, x11);
  dft4(x12, x13, x14, x15);
}

// Every thread holds 16 points of a stage: one radix-16 butterfly, or two radix-8, four
// radix-4 or eight radix-2 ones in the first stage.
cplx v0, v1, v2, v3, v4, v5, v6, v7, v8, v9, v10, v11, v12, v13, v14, v15;

// Which line of the workgroup and which butterfly of that line butterfly b is: lines fastest
// where the array's lines are adjacent in memory (the y axis's columns), so that neighbouring
// invocations touch neighbouring addresses when a stage reads or writes the array itself.
uvec2 line_and_index(uint b, uint per_line, bool lines_fastest) {
  return lines_fastest ? uvec2(b % LINES, b / LINES) : uvec2(b / per_line, b % per_line);
}

cplx fetch(uint l, uint e) {
  const uint lo = group_x() * LINES + l;
  // Every workgroup full (LINES divides LINES_LO, always so for powers of two): no test, so no
  // divergent control flow for the driver to mask.
  if (LINES_LO % LINES == 0u) return load(group_batch(), gl_WorkGroupID.y, lo, e);
  return lo < LINES_LO ? load(group_batch(), gl_WorkGroupID.y, lo, e) : cplx(0);
}

void put(uint l, uint e, cplx v) {
  const uint lo = group_x() * LINES + l;
  if (LINES_LO % LINES != 0u && lo >= LINES_LO) return;
  if (has(SPLIT_TWIDDLE)) {
    const uint n2 = has(SPLIT_BY_HI) ? gl_WorkGroupID.y : lo;
    const cplx w = split_twiddle[(n2 * e) % SPLIT_N];
    v = mul(v, has(INVERSE) ? cplx(w.x, -w.y) : w);
  }
  store(group_batch(), gl_WorkGroupID.y, lo, e, v);
}

// Sixteen values to the array (last stage) or to shared memory: element `first + q·stride` of
// line l gets the q-th value.
void write16(bool to_array, uint l, uint first, uint stride, cplx y0, cplx y1, cplx y2, cplx y3,
             cplx y4, cplx y5, cplx y6, cplx y7, cplx y8, cplx y9, cplx y10, cplx y11,
             cplx y12, cplx y13, cplx y14, cplx y15) {
  if (to_array) {
    put(l, first, y0); put(l, first + stride, y1); put(l, first + 2u * stride, y2); put(l, first + 3u * stride, y3);
    put(l, first + 4u * stride, y4); put(l, first + 5u * stride, y5); put(l, first + 6u * stride, y6); put(l, first + 7u * stride, y7);
    put(l, first + 8u * stride, y8); put(l, first + 9u * stride, y9); put(l, first + 10u * stride, y10); put(l, first + 11u * stride, y11);
    put(l, first + 12u * stride, y12); put(l, first + 13u * stride, y13); put(l, first + 14u * stride, y14); put(l, first + 15u * stride, y15);
    return;
  }
  const uint at = (PING_PONG == 1u ? SHARED_POINTS - current : current) + shared_index(l, first);
  const uint s = stride * element_pitch();
  line[at] = y0; line[at + s] = y1; line[at + 2u * s] = y2; line[at + 3u * s] = y3;
  line[at + 4u * s] = y4; line[at + 5u * s] = y5; line[at + 6u * s] = y6; line[at + 7u * s] = y7;
  line[at + 8u * s] = y8; line[at + 9u * s] = y9; line[at + 10u * s] = y10; line[at + 11u * s] = y11;
  line[at + 12u * s] = y12; line[at + 13u * s] = y13; line[at + 14u * s] = y14; line[at + 15u * s] = y15;
}

// Values of butterfly b (radix R < 16: 16/R of them per thread, t + u·T) to the array or to
// shared memory, x[i·R + q] in the first stage.
void put_small(bool to_array, uvec2 li, uint q, cplx v) {
  if (to_array) put(li.x, q, v);  // the only stage: N = R, i = 0
  else line[(PING_PONG == 1u ? SHARED_POINTS - current : current) + shared_index(li.x, li.y * FIRST_RADIX + q)] = v;
}

// The first stage (span 1, no twiddles) of radix FIRST_RADIX, read from the array itself:
// butterfly i of a line reads x[i + j·N/R] and writes x[i·R + q] — to shared memory, or, when
// it is the only stage (N = R), to the array.
void first_stage() {
  const uint t = gl_LocalInvocationID.x, T = gl_WorkGroupSize.x;
  const bool last = FIRST_RADIX == N;
  const bool fastest = last ? has(DESTINATION_LINE_FASTEST) : has(SOURCE_LINE_FASTEST);
  const uint step = N / FIRST_RADIX;
  if (FIRST_RADIX == 16u) {
    const uvec2 li = line_and_index(t, step, fastest);
    const uint l = li.x, i = li.y;
    v0 = fetch(l, i); v1 = fetch(l, i + step); v2 = fetch(l, i + 2u * step); v3 = fetch(l, i + 3u * step);
    v4 = fetch(l, i + 4u * step); v5 = fetch(l, i + 5u * step); v6 = fetch(l, i + 6u * step); v7 = fetch(l, i + 7u * step);
    v8 = fetch(l, i + 8u * step); v9 = fetch(l, i + 9u * step); v10 = fetch(l, i + 10u * step); v11 = fetch(l, i + 11u * step);
    v12 = fetch(l, i + 12u * step); v13 = fetch(l, i + 13u * step); v14 = fetch(l, i + 14u * step); v15 = fetch(l, i + 15u * step);
    dft16(v0, v1, v2, v3, v4, v5, v6, v7, v8, v9, v10, v11, v12, v13, v14, v15);
    write16(last, l, last ? 0u : i * 16u, 1u, v0, v4, v8, v12, v1, v5, v9, v13, v2, v6, v10, v14, v3, v7, v11, v15);
  } else if (FIRST_RADIX == 8u) {
    const uvec2 a = line_and_index(t, step, fastest), b = line_and_index(t + T, step, fastest);
    v0 = fetch(a.x, a.y); v1 = fetch(a.x, a.y + step); v2 = fetch(a.x, a.y + 2u * step); v3 = fetch(a.x, a.y + 3u * step);
    v4 = fetch(a.x, a.y + 4u * step); v5 = fetch(a.x, a.y + 5u * step); v6 = fetch(a.x, a.y + 6u * step); v7 = fetch(a.x, a.y + 7u * step);
    v8 = fetch(b.x, b.y); v9 = fetch(b.x, b.y + step); v10 = fetch(b.x, b.y + 2u * step); v11 = fetch(b.x, b.y + 3u * step);
    v12 = fetch(b.x, b.y + 4u * step); v13 = fetch(b.x, b.y + 5u * step); v14 = fetch(b.x, b.y + 6u * step); v15 = fetch(b.x, b.y + 7u * step);
    dft8(v0, v1, v2, v3, v4, v5, v6, v7);
    dft8(v8, v9, v10, v11, v12, v13, v14, v15);
    put_small(last, a, 0u, v0); put_small(last, a, 1u, v1); put_small(last, a, 2u, v2); put_small(last, a, 3u, v3);
    put_small(last, a, 4u, v4); put_small(last, a, 5u, v5); put_small(last, a, 6u, v6); put_small(last, a, 7u, v7);
    put_small(last, b, 0u, v8); put_small(last, b, 1u, v9); put_small(last, b, 2u, v10); put_small(last, b, 3u, v11);
    put_small(last, b, 4u, v12); put_small(last, b, 5u, v13); put_small(last, b, 6u, v14); put_small(last, b, 7u, v15);
  } else if (FIRST_RADIX == 4u) {
    const uvec2 a = line_and_index(t, step, fastest), b = line_and_index(t + T, step, fastest);
    const uvec2 c = line_and_index(t + 2u * T, step, fastest), d = line_and_index(t + 3u * T, step, fastest);
    v0 = fetch(a.x, a.y); v1 = fetch(a.x, a.y + step); v2 = fetch(a.x, a.y + 2u * step); v3 = fetch(a.x, a.y + 3u * step);
    v4 = fetch(b.x, b.y); v5 = fetch(b.x, b.y + step); v6 = fetch(b.x, b.y + 2u * step); v7 = fetch(b.x, b.y + 3u * step);
    v8 = fetch(c.x, c.y); v9 = fetch(c.x, c.y + step); v10 = fetch(c.x, c.y + 2u * step); v11 = fetch(c.x, c.y + 3u * step);
    v12 = fetch(d.x, d.y); v13 = fetch(d.x, d.y + step); v14 = fetch(d.x, d.y + 2u * step); v15 = fetch(d.x, d.y + 3u * step);
    dft4(v0, v1, v2, v3); dft4(v4, v5, v6, v7); dft4(v8, v9, v10, v11); dft4(v12, v13, v14, v15);
    put_small(last, a, 0u, v0); put_small(last, a, 1u, v1); put_small(last, a, 2u, v2); put_small(last, a, 3u, v3);
    put_small(last, b, 0u, v4); put_small(last, b, 1u, v5); put_small(last, b, 2u, v6); put_small(last, b, 3u, v7);
    put_small(last, c, 0u, v8); put_small(last, c, 1u, v9); put_small(last, c, 2u, v10); put_small(last, c, 3u, v11);
    put_small(last, d, 0u, v12); put_small(last, d, 1u, v13); put_small(last, d, 2u, v14); put_small(last, d, 3u, v15);
  } else {
    // Named, not an array (see dft2): butterflies t + u·T, u = 0 … 7, so that neighbouring
    // invocations take neighbouring butterflies.
    const uvec2 b0 = line_and_index(t, step, fastest), b1 = line_and_index(t + 1u * T, step, fastest);
    const uvec2 b2 = line_and_index(t + 2u * T, step, fastest), b3 = line_and_index(t + 3u * T, step, fastest);
    const uvec2 b4 = line_and_index(t + 4u * T, step, fastest), b5 = line_and_index(t + 5u * T, step, fastest);
    const uvec2 b6 = line_and_index(t + 6u * T, step, fastest), b7 = line_and_index(t + 7u * T, step, fastest);
    v0 = fetch(b0.x, b0.y); v1 = fetch(b0.x, b0.y + step); v2 = fetch(b1.x, b1.y); v3 = fetch(b1.x, b1.y + step);
    v4 = fetch(b2.x, b2.y); v5 = fetch(b2.x, b2.y + step); v6 = fetch(b3.x, b3.y); v7 = fetch(b3.x, b3.y + step);
    v8 = fetch(b4.x, b4.y); v9 = fetch(b4.x, b4.y + step); v10 = fetch(b5.x, b5.y); v11 = fetch(b5.x, b5.y + step);
    v12 = fetch(b6.x, b6.y); v13 = fetch(b6.x, b6.y + step); v14 = fetch(b7.x, b7.y); v15 = fetch(b7.x, b7.y + step);
    dft2(v0, v1); dft2(v2, v3); dft2(v4, v5); dft2(v6, v7);
    dft2(v8, v9); dft2(v10, v11); dft2(v12, v13); dft2(v14, v15);
    put_small(last, b0, 0u, v0); put_small(last, b0, 1u, v1); put_small(last, b1, 0u, v2); put_small(last, b1, 1u, v3);
    put_small(last, b2, 0u, v4); put_small(last, b2, 1u, v5); put_small(last, b3, 0u, v6); put_small(last, b3, 1u, v7);
    put_small(last, b4, 0u, v8); put_small(last, b4, 1u, v9); put_small(last, b5, 0u, v10); put_small(last, b5, 1u, v11);
    put_small(last, b6, 0u, v12); put_small(last, b6, 1u, v13); put_small(last, b7, 0u, v14); put_small(last, b7, 1u, v15);
  }
  if (!last) barrier();
  swap_copies();
}

// A radix-16 Stockham stage of span p > 1: butterfly i (k = i mod p) reads x[i + j·N/16]
// times w_{16p}^(jk) and writes x[(i − k)·16 + k + q·p] — the last stage (16p = N, so k = i)
// straight to the array's element i + q·N/16. Twiddles: w^1, w^2, w^4 and w^8 from the table,
// the other eleven as products of them (at most three roundings deeper; within the bound).
void radix16_stage(const uint p) {
  const uint t = gl_LocalInvocationID.x;
  const bool last = 16u * p == N;
  const uint step = N / 16u;
  const uvec2 li = line_and_index(t, step, columns_pass() || (last && has(DESTINATION_LINE_FASTEST)));
  const uint l = li.x, i = li.y, k = i & (p - 1u), at = current + shared_index(l, i);
  const uint step_at = step * element_pitch();
  const uint w = k * (N / (16u * p));  // twiddle index of j = 1
  const cplx w1 = twiddle(w), w2 = twiddle(2u * w), w4 = twiddle(4u * w), w8 = twiddle(8u * w);
  const cplx w3 = mul(w2, w1), w5 = mul(w4, w1), w6 = mul(w4, w2), w7 = mul(w4, w3);
  v0 = line[at];
  v1 = mul(line[at + step_at], w1);
  v2 = mul(line[at + 2u * step_at], w2);
  v3 = mul(line[at + 3u * step_at], w3);
  v4 = mul(line[at + 4u * step_at], w4);
  v5 = mul(line[at + 5u * step_at], w5);
  v6 = mul(line[at + 6u * step_at], w6);
  v7 = mul(line[at + 7u * step_at], w7);
  v8 = mul(line[at + 8u * step_at], w8);
  v9 = mul(line[at + 9u * step_at], mul(w8, w1));
  v10 = mul(line[at + 10u * step_at], mul(w8, w2));
  v11 = mul(line[at + 11u * step_at], mul(w8, w3));
  v12 = mul(line[at + 12u * step_at], mul(w8, w4));
  v13 = mul(line[at + 13u * step_at], mul(w8, w5));
  v14 = mul(line[at + 14u * step_at], mul(w8, w6));
  v15 = mul(line[at + 15u * step_at], mul(w8, w7));
  dft16(v0, v1, v2, v3, v4, v5, v6, v7, v8, v9, v10, v11, v12, v13, v14, v15);
  if (!last && PING_PONG == 0u) barrier();
  write16(last, l, last ? i : (i - k) * 16u + k, last ? step : p,
          v0, v4, v8, v12, v1, v5, v9, v13, v2, v6, v10, v14, v3, v7, v11, v15);
  if (!last) barrier();
  swap_copies();
}

// A radix-8 Stockham stage of span p > 1, two butterflies a thread (i = t and t + N/16 of
// its line): butterfly i (k = i mod p) reads x[i + j·N/8] times w_{8p}^(jk) and writes
// x[(i − k)·8 + k + q·p]; the last stage (8p = N) writes element i + q·N/8 of the array.
void radix8_pair(const uint p, const uint l, const uint i, inout cplx x0,
                 inout cplx x1, inout cplx x2, inout cplx x3, inout cplx x4, inout cplx x5,
                 inout cplx x6, inout cplx x7) {
  const uint step = N / 8u, k = i & (p - 1u), at = current + shared_index(l, i);
  const uint step_at = step * element_pitch();
  const uint w = k * (N / (8u * p));
  const cplx w1 = twiddle(w), w2 = twiddle(2u * w), w4 = twiddle(4u * w);
  const cplx w3 = mul(w2, w1);
  x0 = line[at];
  x1 = mul(line[at + step_at], w1);
  x2 = mul(line[at + 2u * step_at], w2);
  x3 = mul(line[at + 3u * step_at], w3);
  x4 = mul(line[at + 4u * step_at], w4);
  x5 = mul(line[at + 5u * step_at], mul(w4, w1));
  x6 = mul(line[at + 6u * step_at], mul(w4, w2));
  x7 = mul(line[at + 7u * step_at], mul(w4, w3));
  dft8(x0, x1, x2, x3, x4, x5, x6, x7);
}
void radix8_put(const uint p, const bool last, const uint l, const uint i, cplx x0, cplx x1,
                cplx x2, cplx x3, cplx x4, cplx x5, cplx x6, cplx x7) {
  const uint step = N / 8u, k = i & (p - 1u);
  if (last) {
    put(l, i, x0); put(l, i + step, x1); put(l, i + 2u * step, x2); put(l, i + 3u * step, x3);
    put(l, i + 4u * step, x4); put(l, i + 5u * step, x5); put(l, i + 6u * step, x6); put(l, i + 7u * step, x7);
    return;
  }
  const uint at = (PING_PONG == 1u ? SHARED_POINTS - current : current) + shared_index(l, (i - k) * 8u + k);
  const uint s = p * element_pitch();
  line[at] = x0; line[at + s] = x1; line[at + 2u * s] = x2; line[at + 3u * s] = x3;
  line[at + 4u * s] = x4; line[at + 5u * s] = x5; line[at + 6u * s] = x6; line[at + 7u * s] = x7;
}
void radix8_stage(const uint p) {
  const uint t = gl_LocalInvocationID.x, T = gl_WorkGroupSize.x;
  const bool last = 8u * p == N;
  const bool fastest = columns_pass() || (last && has(DESTINATION_LINE_FASTEST));
  const uvec2 a = line_and_index(t, N / 8u, fastest), b = line_and_index(t + T, N / 8u, fastest);
  radix8_pair(p, a.x, a.y, v0, v1, v2, v3, v4, v5, v6, v7);
  radix8_pair(p, b.x, b.y, v8, v9, v10, v11, v12, v13, v14, v15);
  if (!last && PING_PONG == 0u) barrier();
  radix8_put(p, last, a.x, a.y, v0, v1, v2, v3, v4, v5, v6, v7);
  radix8_put(p, last, b.x, b.y, v8, v9, v10, v11, v12, v13, v14, v15);
  if (!last) barrier();
  swap_copies();
}

#ifdef SWELL_SHUFFLE
// The subgroup variant (fft_lines_shuffle_*, 16 ≤ N ≤ 2048; docs/vulkan.md §Kernels): one
// radix-16 step in registers, at most one exchange through shared memory, the rest across the
// lanes of a subgroup with subgroupShuffleXor — on lavapipe a shared-memory store and load cost
// about 4.5 ns an invocation and a shuffle 0.2 ns (the lanes of a SIMD register). For a line
// of N = 16·T points, thread t = lane + L·g (L = min(8, T) lanes, G = T/L groups):
//   X[k1 + 16 (c + G d)] = Σ_lane w_L^(lane·d) w_T^(lane·c) Σ_g w_G^(g·c) Y[lane + L g][k1],
//   Y[t][k1] = w_N^(t·k1) Σ_r w_16^(r·k1) x[t + T r]
// (four-step twice: N = 16·T, T = G·L). Step A: x[t + T r] → DFT16 over r, twiddles. Step B
// (G > 1): Y through shared memory so that thread (lane, g') holds, for k1 = g'·16/G + s, all
// g (register s·G + g) → DFT_G, twiddles w_T^(lane·c). Step C (L > 1): an L×L transpose of
// registers and lanes by shuffles (register bit ↔ lane bit, one XOR level a bit) → DFT_L.
const uint LANES = N >= 128u ? 8u : N / 16u;
const uint GROUPS = N / (16u * LANES);

// The register that dft16 leaves X[k] in is 4 (k mod 4) + k div 4, and that map is its own
// inverse: register ρ holds X[4 (ρ mod 4) + ρ div 4].
uint dft16_index(uint rho) { return 4u * (rho % 4u) + rho / 4u; }

// Register-lane transpose of a block of L registers: level s swaps register bit s with lane bit s.
void swap_level(const uint s, const uint lane, inout cplx a, inout cplx b) {
  const bool upper = (lane & s) != 0u;
  const cplx received = subgroupShuffleXor(upper ? a : b, s);
  if (upper) a = received; else b = received;
}
void transpose2(const uint lane, inout cplx x0, inout cplx x1) { swap_level(1u, lane, x0, x1); }
void transpose4(const uint lane, inout cplx x0, inout cplx x1, inout cplx x2, inout cplx x3) {
  swap_level(2u, lane, x0, x2); swap_level(2u, lane, x1, x3);
  swap_level(1u, lane, x0, x1); swap_level(1u, lane, x2, x3);
}
void transpose8(const uint lane, inout cplx x0, inout cplx x1, inout cplx x2, inout cplx x3,
                inout cplx x4, inout cplx x5, inout cplx x6, inout cplx x7) {
  swap_level(4u, lane, x0, x4); swap_level(4u, lane, x1, x5); swap_level(4u, lane, x2, x6); swap_level(4u, lane, x3, x7);
  swap_level(2u, lane, x0, x2); swap_level(2u, lane, x1, x3); swap_level(2u, lane, x4, x6); swap_level(2u, lane, x5, x7);
  swap_level(1u, lane, x0, x1); swap_level(1u, lane, x2, x3); swap_level(1u, lane, x4, x5); swap_level(1u, lane, x6, x7);
}

// F(ρ, register ρ) for the 16 registers: straight-line code with constant register indices.
#define SWELL_EACH16(F) F(0u, v0) F(1u, v1) F(2u, v2) F(3u, v3) F(4u, v4) F(5u, v5) F(6u, v6) \
  F(7u, v7) F(8u, v8) F(9u, v9) F(10u, v10) F(11u, v11) F(12u, v12) F(13u, v13) F(14u, v14) F(15u, v15)

// w^m, 0 ≤ m < 16, from w, w², w⁴ and w⁸ (read from the table) by at most three products, as
// radix16_stage makes its twiddles.
cplx power_of(const uint m, cplx w1, cplx w2, cplx w4, cplx w8) {
  cplx w = cplx(1, 0);
  if ((m & 1u) != 0u) w = w1;
  if ((m & 2u) != 0u) w = (m & 1u) != 0u ? mul(w, w2) : w2;
  if ((m & 4u) != 0u) w = (m & 3u) != 0u ? mul(w, w4) : w4;
  if ((m & 8u) != 0u) w = (m & 7u) != 0u ? mul(w, w8) : w8;
  return w;
}

void shuffle_main() {
  const uint T = N / 16u;
  const uint tl = gl_SubgroupID * gl_SubgroupSize + gl_SubgroupInvocationID;
  const uint l = tl / T, t = tl % T, lane = t % LANES, g = t / LANES;
  // Step A.
#define SWELL_FETCH(rho, v) v = fetch(l, t + (rho) * T);
  SWELL_EACH16(SWELL_FETCH)
  dft16(v0, v1, v2, v3, v4, v5, v6, v7, v8, v9, v10, v11, v12, v13, v14, v15);
  if (T > 1u) {
    const cplx w1 = twiddle(t), w2 = twiddle(2u * t), w4 = twiddle(4u * t), w8 = twiddle(8u * t);  // 8t < N/2
#define SWELL_TWIDDLE_A(rho, v) if (dft16_index(rho) != 0u) v = mul(v, power_of(dft16_index(rho), w1, w2, w4, w8));
    SWELL_EACH16(SWELL_TWIDDLE_A)
  }
  // Step B.
  if (GROUPS > 1u) {
    const uint base = l * N;
#define SWELL_STORE_Y(rho, v) line[base + t * 16u + dft16_index(rho)] = v;
    SWELL_EACH16(SWELL_STORE_Y)
    barrier();
    // Register ρ = s·G + gg takes Y[gg·L + lane][g·16/G + s].
#define SWELL_LOAD_Y(rho, v) v = line[base + (((rho) % GROUPS) * LANES + lane) * 16u + g * (16u / GROUPS) + (rho) / GROUPS];
    SWELL_EACH16(SWELL_LOAD_Y)
    if (GROUPS == 2u) {
      dft2(v0, v1); dft2(v2, v3); dft2(v4, v5); dft2(v6, v7);
      dft2(v8, v9); dft2(v10, v11); dft2(v12, v13); dft2(v14, v15);
    } else if (GROUPS == 4u) {
      dft4(v0, v1, v2, v3); dft4(v4, v5, v6, v7); dft4(v8, v9, v10, v11); dft4(v12, v13, v14, v15);
    } else if (GROUPS == 8u) {
      dft8(v0, v1, v2, v3, v4, v5, v6, v7); dft8(v8, v9, v10, v11, v12, v13, v14, v15);
    } else {
      dft16(v0, v1, v2, v3, v4, v5, v6, v7, v8, v9, v10, v11, v12, v13, v14, v15);
    }
    // Twiddles w_T^(lane·c) = w_N^(16·lane·c), c the DFT_G output a register holds.
    if (LANES > 1u) {
      const uint u = 16u * lane;
      // Powers beyond G − 1 are never used; their indices wrap (mod N) to stay in the table.
      const cplx w1 = twiddle(u), w2 = twiddle((2u * u) % N), w4 = twiddle((4u * u) % N), w8 = twiddle((8u * u) % N);
#define SWELL_C_OF(rho) (GROUPS == 16u ? dft16_index(rho) : (rho) % GROUPS)
#define SWELL_TWIDDLE_B(rho, v) if (SWELL_C_OF(rho) != 0u) v = mul(v, power_of(SWELL_C_OF(rho), w1, w2, w4, w8));
      SWELL_EACH16(SWELL_TWIDDLE_B)
    }
  }
  // Step C.
  if (LANES == 2u) {
    transpose2(lane, v0, v1); transpose2(lane, v2, v3); transpose2(lane, v4, v5); transpose2(lane, v6, v7);
    transpose2(lane, v8, v9); transpose2(lane, v10, v11); transpose2(lane, v12, v13); transpose2(lane, v14, v15);
    dft2(v0, v1); dft2(v2, v3); dft2(v4, v5); dft2(v6, v7);
    dft2(v8, v9); dft2(v10, v11); dft2(v12, v13); dft2(v14, v15);
  } else if (LANES == 4u) {
    transpose4(lane, v0, v1, v2, v3); transpose4(lane, v4, v5, v6, v7);
    transpose4(lane, v8, v9, v10, v11); transpose4(lane, v12, v13, v14, v15);
    dft4(v0, v1, v2, v3); dft4(v4, v5, v6, v7); dft4(v8, v9, v10, v11); dft4(v12, v13, v14, v15);
  } else if (LANES == 8u) {
    transpose8(lane, v0, v1, v2, v3, v4, v5, v6, v7);
    transpose8(lane, v8, v9, v10, v11, v12, v13, v14, v15);
    dft8(v0, v1, v2, v3, v4, v5, v6, v7); dft8(v8, v9, v10, v11, v12, v13, v14, v15);
  }
  // Register b·L + d now holds, for ρ = b·L + lane (the register it came from before the
  // transpose), X[k1 + 16 (c + G d)].
#define SWELL_PUT(rho, v) { \
    const uint from = ((rho) / LANES) * LANES + lane; \
    const uint k1 = GROUPS > 1u ? g * (16u / GROUPS) + from / GROUPS : dft16_index(from); \
    const uint c = GROUPS > 1u ? SWELL_C_OF(from) : 0u; \
    put(l, k1 + 16u * (c + GROUPS * ((rho) % LANES)), v); }
  SWELL_EACH16(SWELL_PUT)
}
#endif

void transform() {
#ifdef SWELL_SHUFFLE
  shuffle_main();
  return;
#endif
  if (FIRST_RADIX == 1u) {  // N = 1: a copy (with the flags' conversions)
    const uint t = gl_LocalInvocationID.x;
    for (uint l = t; l < LINES; l += gl_WorkGroupSize.x) put(l, 0u, fetch(l, 0u));
    return;
  }
  first_stage();
  uint p = FIRST_RADIX;
  for (uint stage = 0u; stage < RADIX8_STAGES; ++stage, p *= 8u) radix8_stage(p);
  for (; p < N; p *= 16u) radix16_stage(p);
}

void main() {
  transform();
  frame_finish();
}
