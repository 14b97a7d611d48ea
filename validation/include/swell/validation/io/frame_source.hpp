#pragma once
// A surface's frames as the ocean checks read them: in frame order, one at a time, from memory
// (a FrameSequence) or from the files a case names, read ahead on their own thread while the
// caller works on the frame before. Through a file source the gate's memory is a few frames'
// fields, whatever the frame count (docs/performance.md §6).
#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "swell/reference/fields.hpp"
#include "swell/validation/io/frame_io.hpp"

namespace swell::validation {

class FrameSource {
 public:
  using Visit = std::function<void(std::size_t frame, const reference::FieldFrame&)>;
  virtual ~FrameSource() = default;

  // The samples, as FrameSequence holds them (a lattice's grid holds its lengths).
  virtual reference::Sampling sampling() const = 0;
  virtual std::size_t size() const = 0;  // frames
  virtual double time(std::size_t frame) const = 0;
  virtual bool has(reference::Field field) const = 0;  // in every frame
  // The stored numbers' precision (FrameSequence's unit_roundoff and storage_roundoff). A file
  // source knows it from frame 0 until one stream has seen every frame; `precision_final` says
  // whether it has. A caller whose work depends on it streams again when it changed.
  virtual FramePrecision precision() const = 0;
  virtual bool precision_final() const = 0;
  // Frames 0 … size()−1 in order to `visit`, each alive during its call only, with the fields
  // `keep` accepts (all when empty). Errors of reading are thrown at the frame they belong to.
  virtual void stream(const FieldFilter& keep, const Visit& visit) const = 0;
  // One frame, out of order (what a check's diagnosis reads again), with the fields `keep`
  // accepts.
  virtual std::shared_ptr<const reference::FieldFrame> frame(std::size_t f,
                                                             const FieldFilter& keep = {}) const = 0;
  std::vector<reference::Field> fields() const;  // those present, in swell's order
};

// Frames already in memory: nothing is copied.
class MemoryFrameSource final : public FrameSource {
 public:
  explicit MemoryFrameSource(const reference::FrameSequence& frames) : frames_(frames) {}
  reference::Sampling sampling() const override { return frames_.sampling(); }
  std::size_t size() const override { return frames_.frames.size(); }
  double time(std::size_t frame) const override { return frames_.frames[frame].time; }
  bool has(reference::Field field) const override { return frames_.has(field); }
  FramePrecision precision() const override { return {frames_.unit_roundoff, frames_.storage_roundoff}; }
  bool precision_final() const override { return true; }
  void stream(const FieldFilter& keep, const Visit& visit) const override;
  std::shared_ptr<const reference::FieldFrame> frame(std::size_t f, const FieldFilter& keep = {}) const override;

 private:
  const reference::FrameSequence& frames_;
};

// The frames a case file names ([input], or `pattern_override`), read as read_frames reads them
// (every file checked, every message the same) but one at a time: a stream holds the frame being
// visited and the one being read, no more. Frame 0 is read when the source is made (its precision
// stands for all until a stream has seen every frame) and kept until the first stream passes it.
class FileFrameSource final : public FrameSource {
 public:
  // `threads` decode each file (its compressed blocks side by side); the frames themselves are
  // read one after another.
  FileFrameSource(const CaseFile& case_file, const std::string& pattern_override = "", int threads = 1);
  reference::Sampling sampling() const override { return sampling_; }
  std::size_t size() const override { return std::size_t(reader_.frames()); }
  double time(std::size_t frame) const override { return reader_.ocean().time(int(frame)); }
  bool has(reference::Field field) const override { return reader_.input().channels.count(field) > 0; }
  FramePrecision precision() const override { return precision_; }
  bool precision_final() const override { return final_; }
  void stream(const FieldFilter& keep, const Visit& visit) const override;
  std::shared_ptr<const reference::FieldFrame> frame(std::size_t f, const FieldFilter& keep = {}) const override;
  // Seconds spent reading files so far (on the reading thread, beside the caller's work).
  double reading_seconds() const { return reading_seconds_; }

 private:
  struct Tally {
    double stored = 0;
    bool all_halves = true;
    void add(const FrameFileReader& reader, double roundoff, const reference::FieldFrame& frame);
  };
  FrameFileReader reader_;
  reference::Sampling sampling_;
  Tally first_tally_;  // frame 0's
  mutable std::shared_ptr<const reference::FieldFrame> first_;  // frame 0, all fields, until streamed
  mutable FramePrecision precision_;
  mutable bool final_ = false;
  mutable double reading_seconds_ = 0;
};

}  // namespace swell::validation
