#version 450
// The unpack kernel of a device-resident ocean frame (docs/synthesis.md §vulkan): from the
// inverse transforms of the eight real fields to the six output fields, as
// Synthesizer::State::unpack does on the host (impls/src/synthesizer.cpp, unpack_body):
//   h, slope_x, slope_y, disp_x, disp_y   copied, times their inverse scales (powers of two:
//                                         exact, and 0 for a field that is zero by definition)
//   jacobian                              J = (1 + λ∂Dx/∂x)(1 + λ∂Dy/∂y) − (λ∂Dx/∂y)²
//                                         (conventions §Derived fields)
// PAIRS: the input is four complex planes (h, ∂h/∂x), (∂h/∂y, λDx), (λDy, λ∂Dx/∂x),
// (λ∂Dy/∂y, λ∂Dx/∂y), real and imaginary parts; otherwise eight real planes in that order.
//
// Memory accesses are what it costs on lavapipe (each one a loop over the SIMD lanes): in fp32
// an invocation takes two adjacent samples and moves 64-bit words — a complex value, or the
// pair of samples of one field — as doubles whose bits are the two floats (never used as
// numbers, so the bits stay as written); the inverse scales are push constants.
//
// The probe: a non-finite value is a bug the synthesizer reports (InternalError naming the
// field and the case, never a frame with infinities). Each invocation that wrote one adds 1 to
// `non_finite`; the host reads it with the frame. The test is on the exponent bits, which no
// compiler's assumptions about NaN (fast-math) can fold away, as `isnan` could be.
//
// Planes are bound one per binding; a tiny grid's planes, smaller than
// minStorageBufferOffsetAlignment, share one binding of the whole buffer, plane p then starting
// at word p · input_stride (field_stride for the outputs; 0 otherwise).
#ifdef SWELL_FP64
#define real double
#else
#define real float
#endif

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const bool PAIRS = true;

// Every plane is an array of 64-bit words: in fp64 a word is one sample of a field or one part
// of a complex sample (re at word 2p, im at 2p + 1); in fp32 a word is a complex sample (PAIRS
// input), or two adjacent samples of a real plane or of a field.
layout(set = 0, binding = 0) buffer Probe { uint non_finite; };
layout(set = 0, binding = 1) readonly buffer Input0 { double input0[]; };
layout(set = 0, binding = 2) readonly buffer Input1 { double input1[]; };
layout(set = 0, binding = 3) readonly buffer Input2 { double input2[]; };
layout(set = 0, binding = 4) readonly buffer Input3 { double input3[]; };
layout(set = 0, binding = 5) readonly buffer Input4 { double input4[]; };
layout(set = 0, binding = 6) readonly buffer Input5 { double input5[]; };
layout(set = 0, binding = 7) readonly buffer Input6 { double input6[]; };
layout(set = 0, binding = 8) readonly buffer Input7 { double input7[]; };
layout(set = 0, binding = 9) writeonly buffer Field0 { double field0[]; };
layout(set = 0, binding = 10) writeonly buffer Field1 { double field1[]; };
layout(set = 0, binding = 11) writeonly buffer Field2 { double field2[]; };
layout(set = 0, binding = 12) writeonly buffer Field3 { double field3[]; };
layout(set = 0, binding = 13) writeonly buffer Field4 { double field4[]; };
layout(set = 0, binding = 14) writeonly buffer Field5 { double field5[]; };

layout(push_constant) uniform Frame {
  uint count;         // samples per field, nx·ny (even in fp32: powers of two, and not 1×1)
  uint input_stride;  // words from one input plane to the next (0: one binding per plane)
  uint field_stride;  // likewise for the fields
  uint reserved;
  real inverse_scale[8];  // undoes the field scales; 0 for a field that is zero by definition
} frame;

bool finite(float v) { return (floatBitsToUint(v) & 0x7f800000u) != 0x7f800000u; }
bool finite(double v) { return (unpackDouble2x32(v).y & 0x7ff00000u) != 0x7ff00000u; }

#ifdef SWELL_FP64

void main() {
  const uint p = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  if (p >= frame.count) return;
  // The eight real fields at sample p, in packing order, on named values (no arrays, no loops).
  const uint s = frame.input_stride;
  double v0, v1, v2, v3, v4, v5, v6, v7;
  if (PAIRS) {
    v0 = input0[2u * p];              v1 = input0[2u * p + 1u];
    v2 = input1[s + 2u * p];          v3 = input1[s + 2u * p + 1u];
    v4 = input2[2u * s + 2u * p];     v5 = input2[2u * s + 2u * p + 1u];
    v6 = input3[3u * s + 2u * p];     v7 = input3[3u * s + 2u * p + 1u];
  } else {
    v0 = input0[p];          v1 = input1[s + p];      v2 = input2[2u * s + p];
    v3 = input3[3u * s + p]; v4 = input4[4u * s + p]; v5 = input5[5u * s + p];
    v6 = input6[6u * s + p]; v7 = input7[7u * s + p];
  }
  const double h = v0 * frame.inverse_scale[0], sx = v1 * frame.inverse_scale[1];
  const double sy = v2 * frame.inverse_scale[2], dx = v3 * frame.inverse_scale[3];
  const double dy = v4 * frame.inverse_scale[4];
  const double dxx = v5 * frame.inverse_scale[5], dyy = v6 * frame.inverse_scale[6];
  const double dxy = v7 * frame.inverse_scale[7];
  const double jacobian = (1.0lf + dxx) * (1.0lf + dyy) - dxy * dxy;
  const uint f = frame.field_stride;
  field0[p] = h;
  field1[f + p] = sx;
  field2[2u * f + p] = sy;
  field3[3u * f + p] = dx;
  field4[4u * f + p] = dy;
  field5[5u * f + p] = jacobian;
  if (!(finite(h) && finite(sx) && finite(sy) && finite(dx) && finite(dy) && finite(jacobian))) {
    atomicAdd(non_finite, 1u);
  }
}

#else

vec2 floats(double w) { return uintBitsToFloat(unpackDouble2x32(w)); }
double word(float a, float b) { return packDouble2x32(uvec2(floatBitsToUint(a), floatBitsToUint(b))); }

void main() {
  // Samples 2q and 2q + 1.
  const uint q = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  if (q >= frame.count / 2u) return;
  const uint s = frame.input_stride;
  vec2 v0, v1, v2, v3, v4, v5, v6, v7;  // field r at the two samples
  if (PAIRS) {
    // Complex word w of plane P holds sample w's (re, im) = (field 2P, field 2P + 1).
    const vec2 a0 = floats(input0[2u * q]), b0 = floats(input0[2u * q + 1u]);
    const vec2 a1 = floats(input1[s + 2u * q]), b1 = floats(input1[s + 2u * q + 1u]);
    const vec2 a2 = floats(input2[2u * s + 2u * q]), b2 = floats(input2[2u * s + 2u * q + 1u]);
    const vec2 a3 = floats(input3[3u * s + 2u * q]), b3 = floats(input3[3u * s + 2u * q + 1u]);
    v0 = vec2(a0.x, b0.x); v1 = vec2(a0.y, b0.y);
    v2 = vec2(a1.x, b1.x); v3 = vec2(a1.y, b1.y);
    v4 = vec2(a2.x, b2.x); v5 = vec2(a2.y, b2.y);
    v6 = vec2(a3.x, b3.x); v7 = vec2(a3.y, b3.y);
  } else {
    // Word w of a real plane holds samples 2w and 2w + 1.
    v0 = floats(input0[q]);          v1 = floats(input1[s + q]);
    v2 = floats(input2[2u * s + q]); v3 = floats(input3[3u * s + q]);
    v4 = floats(input4[4u * s + q]); v5 = floats(input5[5u * s + q]);
    v6 = floats(input6[6u * s + q]); v7 = floats(input7[7u * s + q]);
  }
  const vec2 h = v0 * frame.inverse_scale[0], sx = v1 * frame.inverse_scale[1];
  const vec2 sy = v2 * frame.inverse_scale[2], dx = v3 * frame.inverse_scale[3];
  const vec2 dy = v4 * frame.inverse_scale[4];
  const vec2 dxx = v5 * frame.inverse_scale[5], dyy = v6 * frame.inverse_scale[6];
  const vec2 dxy = v7 * frame.inverse_scale[7];
  const vec2 jacobian = (1.0 + dxx) * (1.0 + dyy) - dxy * dxy;
  const uint f = frame.field_stride;
  field0[q] = word(h.x, h.y);
  field1[f + q] = word(sx.x, sx.y);
  field2[2u * f + q] = word(sy.x, sy.y);
  field3[3u * f + q] = word(dx.x, dx.y);
  field4[4u * f + q] = word(dy.x, dy.y);
  field5[5u * f + q] = word(jacobian.x, jacobian.y);
  const bool all_finite = finite(h.x) && finite(h.y) && finite(sx.x) && finite(sx.y) &&
                          finite(sy.x) && finite(sy.y) && finite(dx.x) && finite(dx.y) &&
                          finite(dy.x) && finite(dy.y) && finite(jacobian.x) && finite(jacobian.y);
  if (!all_finite) atomicAdd(non_finite, 1u);
}

#endif
