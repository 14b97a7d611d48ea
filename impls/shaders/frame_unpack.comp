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
// The probe: a non-finite value is a bug the synthesizer reports (InternalError naming the
// field and the case, never a frame with infinities). Each invocation that wrote one adds 1 to
// `non_finite`; the host reads it with the frame. The test is on the exponent bits, which no
// compiler's assumptions about NaN (fast-math) can fold away, as `isnan` could be.
#ifdef SWELL_FP64
#define real double
#else
#define real float
#endif

layout(local_size_x_id = 0) in;
layout(constant_id = 1) const bool PAIRS = true;

layout(set = 0, binding = 0) readonly buffer Tables {
  real field_scale[8];
  real inverse_scale[8];
  real wave_number[];
};
layout(set = 0, binding = 1) buffer Probe { uint non_finite; };
layout(set = 0, binding = 2) readonly buffer Input0 { real input0[]; };
layout(set = 0, binding = 3) readonly buffer Input1 { real input1[]; };
layout(set = 0, binding = 4) readonly buffer Input2 { real input2[]; };
layout(set = 0, binding = 5) readonly buffer Input3 { real input3[]; };
layout(set = 0, binding = 6) readonly buffer Input4 { real input4[]; };
layout(set = 0, binding = 7) readonly buffer Input5 { real input5[]; };
layout(set = 0, binding = 8) readonly buffer Input6 { real input6[]; };
layout(set = 0, binding = 9) readonly buffer Input7 { real input7[]; };
layout(set = 0, binding = 10) writeonly buffer Field0 { real field0[]; };
layout(set = 0, binding = 11) writeonly buffer Field1 { real field1[]; };
layout(set = 0, binding = 12) writeonly buffer Field2 { real field2[]; };
layout(set = 0, binding = 13) writeonly buffer Field3 { real field3[]; };
layout(set = 0, binding = 14) writeonly buffer Field4 { real field4[]; };
layout(set = 0, binding = 15) writeonly buffer Field5 { real field5[]; };

layout(push_constant) uniform Frame {
  uint count;          // samples per field, nx·ny
  uint input_base[8];  // element where input plane p starts within its binding
  uint field_base[6];  // likewise for the six fields
} frame;

real get(uint p, uint index) {
  const uint at = frame.input_base[p] + index;
  switch (p) {
    case 0u: return input0[at];
    case 1u: return input1[at];
    case 2u: return input2[at];
    case 3u: return input3[at];
    case 4u: return input4[at];
    case 5u: return input5[at];
    case 6u: return input6[at];
    default: return input7[at];
  }
}

void put(uint f, uint index, real v) {
  const uint at = frame.field_base[f] + index;
  switch (f) {
    case 0u: field0[at] = v; break;
    case 1u: field1[at] = v; break;
    case 2u: field2[at] = v; break;
    case 3u: field3[at] = v; break;
    case 4u: field4[at] = v; break;
    default: field5[at] = v; break;
  }
}

bool finite(real v) {
#ifdef SWELL_FP64
  return (unpackDouble2x32(v).y & 0x7ff00000u) != 0x7ff00000u;
#else
  return (floatBitsToUint(v) & 0x7f800000u) != 0x7f800000u;
#endif
}

void main() {
  const uint p = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
  if (p >= frame.count) return;
  real v[8];  // the eight real fields at sample p, in packing order
  if (PAIRS) {
    for (uint q = 0u; q < 4u; ++q) {
      v[2u * q] = get(q, 2u * p);
      v[2u * q + 1u] = get(q, 2u * p + 1u);
    }
  } else {
    for (uint r = 0u; r < 8u; ++r) v[r] = get(r, p);
  }
  real out_fields[6];
  for (uint f = 0u; f < 5u; ++f) out_fields[f] = v[f] * inverse_scale[f];
  const real dxx = v[5] * inverse_scale[5], dyy = v[6] * inverse_scale[6], dxy = v[7] * inverse_scale[7];
  out_fields[5] = (real(1) + dxx) * (real(1) + dyy) - dxy * dxy;
  bool all_finite = true;
  for (uint f = 0u; f < 6u; ++f) {
    put(f, p, out_fields[f]);
    all_finite = all_finite && finite(out_fields[f]);
  }
  if (!all_finite) atomicAdd(non_finite, 1u);
}
