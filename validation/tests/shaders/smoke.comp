#version 450
// Doubles every element: the smallest compute shader that proves glslc → SPIR-V → device works.
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Data { float values[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < values.length()) values[i] *= 2.0;
}
