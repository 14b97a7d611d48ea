#include "swell/reference/fields.hpp"

#include "swell/reference/errors.hpp"

namespace swell::reference {

std::string field_name(Field field) {
  switch (field) {
    case Field::height: return "height";
    case Field::slope_x: return "slope_x";
    case Field::slope_y: return "slope_y";
    case Field::disp_x: return "disp_x";
    case Field::disp_y: return "disp_y";
    case Field::jacobian: return "jacobian";
  }
  return "?";
}

std::string channel_name(Field field) {
  switch (field) {
    case Field::height: return "h";
    case Field::slope_x: return "sx";
    case Field::slope_y: return "sy";
    case Field::disp_x: return "dx";
    case Field::disp_y: return "dy";
    case Field::jacobian: return "J";
  }
  return "?";
}

Field field_from_name(const std::string& name) {
  for (Field field : kAllFields) {
    if (name == field_name(field) || name == channel_name(field)) return field;
  }
  throw InvalidInput("unknown field '" + name +
                     "'; valid: height (h), slope_x (sx), slope_y (sy), disp_x (dx), disp_y (dy), "
                     "jacobian (J)");
}

bool FrameSequence::has(Field field) const {
  if (frames.empty()) return false;
  for (const auto& frame : frames) {
    if (!frame.fields.count(field)) return false;
  }
  return true;
}

const std::vector<double>& FrameSequence::field(int frame, Field which) const {
  if (frame < 0 || frame >= static_cast<int>(frames.size())) {
    throw InvalidInput("frame " + std::to_string(frame) + " requested of " +
                       std::to_string(frames.size()));
  }
  const auto it = frames[frame].fields.find(which);
  if (it == frames[frame].fields.end()) {
    throw InvalidInput("frame " + std::to_string(frame) + " has no " + field_name(which) +
                       " field");
  }
  return it->second;
}

}  // namespace swell::reference
