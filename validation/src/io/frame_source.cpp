// Frames one at a time (frame_source.hpp): from memory, or from files with a reading thread one
// frame ahead of the caller.
#include "swell/validation/io/frame_source.hpp"

#include "swell/reference/errors.hpp"

#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace swell::validation {

using reference::Field;
using reference::FieldFrame;

std::vector<Field> FrameSource::fields() const {
  std::vector<Field> out;
  for (Field field : reference::kAllFields) {
    if (has(field)) out.push_back(field);
  }
  return out;
}

namespace {

// A frame with only the fields `keep` accepts of `frame` f, copied.
FieldFrame filtered(const FieldFrame& frame, int f, const FieldFilter& keep) {
  FieldFrame out;
  out.time = frame.time;
  for (const auto& [field, values] : frame.fields) {
    if (!keep || keep(f, field)) out.fields[field] = values;
  }
  for (const auto& [field, values] : frame.imaginary) {
    if (!keep || keep(f, field)) out.imaginary[field] = values;
  }
  return out;
}

}  // namespace

void MemoryFrameSource::stream(const FieldFilter&, const Visit& visit) const {
  // The frames in memory are visited as they are: a visitor reads the fields it asked for.
  for (std::size_t f = 0; f < frames_.frames.size(); ++f) visit(f, frames_.frames[f]);
}

std::shared_ptr<const FieldFrame> MemoryFrameSource::frame(std::size_t f, const FieldFilter&) const {
  // Not owned: the sequence outlives the source.
  return std::shared_ptr<const FieldFrame>(&frames_.frames.at(f), [](const FieldFrame*) {});
}

void FileFrameSource::Tally::add(const FrameFileReader& reader, double roundoff, const FieldFrame& frame) {
  stored = std::max(stored, roundoff);
  // Whether every value is a half matters for undeclared float frames only (storage_precision).
  if (all_halves && reader.needs_half_scan(roundoff)) all_halves = all_half_values(frame);
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

FileFrameSource::FileFrameSource(const CaseFile& case_file, const std::string& pattern_override, int threads)
    : reader_(case_file, pattern_override, threads), sampling_(case_file.ocean.sampling()) {
  const auto start = std::chrono::steady_clock::now();
  if (reader_.frames() < 1) throw InvalidInput("no frames to check");
  auto first = std::make_shared<FieldFrame>();
  FrameReadScratch scratch;
  first_tally_.add(reader_, reader_.read(0, *first, scratch), *first);
  precision_ = reader_.precision(first_tally_.stored, first_tally_.all_halves);
  final_ = reader_.frames() == 1;
  if (final_) reader_.require_no_extra_frame();
  first_ = std::move(first);
  reading_seconds_ = seconds_since(start);
}

std::shared_ptr<const FieldFrame> FileFrameSource::frame(std::size_t f, const FieldFilter& keep) const {
  if (f == 0 && first_) return keep ? std::make_shared<FieldFrame>(filtered(*first_, 0, keep)) : first_;
  const auto start = std::chrono::steady_clock::now();
  auto out = std::make_shared<FieldFrame>();
  FrameReadScratch scratch;
  reader_.read(int(f), *out, scratch, keep);
  reading_seconds_ += seconds_since(start);
  return out;
}

void FileFrameSource::stream(const FieldFilter& keep, const Visit& visit) const {
  const std::size_t frames = size();
  // Two slots: the caller visits one while the reading thread fills the other.
  struct Slot {
    FieldFrame frame;
    double roundoff = 0;
    std::exception_ptr error;
    bool ready = false;
  };
  Slot slots[2];
  std::mutex mutex;
  std::condition_variable changed;
  bool stop = false;
  // Frame 0 from what the source kept, when it kept it. It takes slot 0's place until it has
  // been visited, so that no more than two frames are ever held.
  std::shared_ptr<const FieldFrame> first = first_;
  const bool kept_first = bool(first);
  slots[0].ready = kept_first;
  double reading = 0;  // the reading thread's, added once it is joined
  std::thread reader([&] {
    FrameReadScratch scratch;
    for (std::size_t f = kept_first ? 1 : 0; f < frames; ++f) {
      Slot& slot = slots[f % 2];
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return stop || !slot.ready; });
        if (stop) return;
      }
      try {
        const auto start = std::chrono::steady_clock::now();
        slot.roundoff = reader_.read(int(f), slot.frame, scratch, keep);
        reading += seconds_since(start);
      } catch (...) {
        slot.error = std::current_exception();
      }
      {
        std::lock_guard lock(mutex);
        slot.ready = true;
      }
      changed.notify_all();
      if (slot.error) return;
    }
  });
  auto finish = [&] {
    {
      std::lock_guard lock(mutex);
      stop = true;
    }
    changed.notify_all();
    reader.join();
    reading_seconds_ += reading;
  };
  // Frame 0's share of the stored precision, when it is not read again.
  Tally tally = kept_first ? first_tally_ : Tally{};
  try {
    for (std::size_t f = 0; f < frames; ++f) {
      if (f == 0 && kept_first) {
        if (keep) {
          visit(0, filtered(*first, 0, keep));
        } else {
          visit(0, *first);
        }
        first_.reset();  // streamed past: read again if asked for
        first.reset();
        {
          std::lock_guard lock(mutex);
          slots[0].ready = false;
        }
        changed.notify_all();
        continue;
      }
      Slot& slot = slots[f % 2];
      {
        std::unique_lock lock(mutex);
        changed.wait(lock, [&] { return slot.ready; });
      }
      if (slot.error) std::rethrow_exception(slot.error);
      tally.add(reader_, slot.roundoff, slot.frame);
      visit(f, slot.frame);
      {
        std::lock_guard lock(mutex);
        slot.ready = false;
      }
      changed.notify_all();
    }
  } catch (...) {
    finish();
    throw;
  }
  finish();
  if (!final_) {
    reader_.require_no_extra_frame();
    precision_ = reader_.precision(tally.stored, tally.all_halves);
    final_ = true;
  }
}

}  // namespace swell::validation
