#include "mvr/gl/readback_ring.h"

#include <algorithm>
#include <cstring>

#include "mvr/error.h"
#include "mvr/parallel.h"
#include "mvr/timer.h"

namespace mvr {
namespace {

constexpr GLbitfield kMapping = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;

ReadbackStaging gStaging = ReadbackStaging::Auto;

bool stage() {
  return gStaging == ReadbackStaging::Always || (gStaging == ReadbackStaging::Auto && !gl::rendersOnCpu());
}

}  // namespace

void setReadbackStaging(ReadbackStaging staging) { gStaging = staging; }

ReadbackRing::ReadbackRing(size_t slotBytes, int slots)
    : slotBytes_(std::max<size_t>(slotBytes, 1)), layerReader_(gl::Framebuffer::create()) {
  if (!stage()) return;
  slots_.resize(std::max(slots, 1));
  for (Slot& slot : slots_) {
    slot.buffer = gl::Buffer::create();
    gl::NamedBufferStorage(slot.buffer.id(), GLsizeiptr(slotBytes_), nullptr, kMapping);
    slot.bytes = static_cast<const std::byte*>(
        gl::MapNamedBufferRange(slot.buffer.id(), 0, GLsizeiptr(slotBytes_), kMapping));
    if (!slot.bytes) fail("GL", "cannot map a readback buffer of " + std::to_string(slotBytes_) + " bytes");
  }
}

ReadbackRing::~ReadbackRing() {
  // Batches still pending are dropped (an exception is unwinding the
  // render); fences and mappings are released.
  for (Slot& slot : slots_) {
    if (slot.fence) gl::DeleteSync(slot.fence);
    gl::UnmapNamedBuffer(slot.buffer.id());
  }
}

void ReadbackRing::readRows(const RenderTarget& target, int y, int h, std::byte* dst) {
  std::byte* const one[] = {dst};
  read(target, target.readableFramebuffer(y, h), y, h, one);
}

void ReadbackRing::readRowRuns(const RenderTarget& target, int y, int h, std::span<std::byte* const> dsts) {
  if (dsts.empty()) return;
  if (!staged()) {
    // Unstaged reads land in place: one per destination.
    for (size_t k = 0; k < dsts.size(); ++k) readRows(target, y + int(k) * h, h, dsts[k]);
    return;
  }
  const int rows = h * int(dsts.size());
  read(target, target.readableFramebuffer(y, rows), y, rows, {dsts.data(), dsts.size()});
}

void ReadbackRing::readLayer(const RenderTarget& target, int layer, std::byte* dst) {
  // A framebuffer on just this layer: reading the array texture itself
  // (glGetTextureSubImage) may copy every layer on some drivers.
  gl::NamedFramebufferTextureLayer(layerReader_.id(), GL_COLOR_ATTACHMENT0, target.colorTexture(), 0, layer);
  gl::NamedFramebufferReadBuffer(layerReader_.id(), GL_COLOR_ATTACHMENT0);
  std::byte* const one[] = {dst};
  read(target, layerReader_.id(), 0, target.height(), one);
}

void ReadbackRing::readBuffer(GLuint buffer, size_t bytes, std::span<std::byte* const> dsts) {
  if (dsts.empty()) return;
  gl::MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);  // the copy reads what shaders wrote
  const size_t each = bytes / dsts.size();
  if (!staged()) {
    for (size_t k = 0; k < dsts.size(); ++k)
      gl::GetNamedBufferSubData(buffer, GLintptr(k * each), GLsizeiptr(each), dsts[k]);
    return;
  }
  const size_t at = reserve(bytes, dsts);
  gl::CopyNamedBufferSubData(buffer, slots_[current_].buffer.id(), 0, GLintptr(at), GLsizeiptr(bytes));
}

// `bytes` of the current slot for one read, split evenly among dsts once
// the batch lands; returns where in the slot's buffer the GPU writes them.
size_t ReadbackRing::reserve(size_t bytes, std::span<std::byte* const> dsts) {
  Slot& slot = slots_[current_];
  if (slot.used + bytes > slotBytes_) fail("ReadbackRing", "a batch reads more than a slot holds");
  const size_t at = slot.used, each = bytes / dsts.size();
  for (size_t k = 0; k < dsts.size(); ++k) slot.copies.push_back({at + k * each, each, dsts[k]});
  slot.used += bytes;
  return at;
}

// h rows from y, split evenly among dsts (one unless staged).
void ReadbackRing::read(const RenderTarget& target, GLuint framebuffer, int y, int h,
                        std::span<std::byte* const> dsts) {
  const size_t bytes = size_t(target.width()) * h * 4 * Image::channelBytes(target.type());
  gl::BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  if (!staged()) {
    readStoredPixels(y, target.width(), h, target.type(), dsts[0]);
    return;
  }
  const size_t at = reserve(bytes, dsts);
  gl::BindBuffer(GL_PIXEL_PACK_BUFFER, slots_[current_].buffer.id());
  readStoredPixels(y, target.width(), h, target.type(), reinterpret_cast<void*>(at));
  gl::BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

void ReadbackRing::submit(Done done) {
  if (!staged()) {
    done();
    return;
  }
  Slot& slot = slots_[current_];
  slot.fence = gl::FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
  slot.done = std::move(done);
  gl::Flush();  // the fence must reach the GPU before anyone waits on it
  current_ = (current_ + 1) % slots_.size();
  finish(slots_[current_]);
}

void ReadbackRing::drain() {
  for (size_t k = 1; k <= slots_.size(); ++k) finish(slots_[(current_ + k) % slots_.size()]);
}

// One thread copies mapped memory at a few GB/s, under what the transfer
// delivers (an H100 host: 1.23 GB read back in 0.27 s, mostly this copy);
// pieces of a megabyte go to the pool.
void ReadbackRing::copyOut(const Slot& slot) {
  constexpr size_t kPiece = size_t(1) << 20;
  size_t total = 0;
  for (const Copy& c : slot.copies) total += c.bytes;
  if (total < 4 * kPiece || threadCount() < 2) {
    for (const Copy& c : slot.copies) std::memcpy(c.dst, slot.bytes + c.at, c.bytes);
    return;
  }
  std::vector<Copy> pieces;
  for (const Copy& c : slot.copies)
    for (size_t at = 0; at < c.bytes; at += kPiece)
      pieces.push_back({c.at + at, std::min(kPiece, c.bytes - at), c.dst + at});
  parallelFor(0, int(pieces.size()), [&](int k) {
    const Copy& p = pieces[size_t(k)];
    std::memcpy(p.dst, slot.bytes + p.at, p.bytes);
  });
}

void ReadbackRing::finish(Slot& slot) {
  if (!slot.fence) return;
  const Stopwatch watch;
  for (;;) {
    const GLenum result = gl::ClientWaitSync(slot.fence, GL_SYNC_FLUSH_COMMANDS_BIT, 1000000000);
    if (result == GL_ALREADY_SIGNALED || result == GL_CONDITION_SATISFIED) break;
    if (result == GL_WAIT_FAILED) fail("GL", "waiting for a readback failed");
  }
  gl::DeleteSync(slot.fence);
  slot.fence = nullptr;
  copyOut(slot);
  waitSeconds_ += watch.seconds();
  slot.copies.clear();
  slot.used = 0;
  Done done = std::move(slot.done);
  slot.done = nullptr;
  done();
}

}  // namespace mvr
