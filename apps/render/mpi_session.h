#pragma once
// The MPI job a process belongs to when mpirun started it with more than
// one rank; the only file that includes mpi.h. Built only where MPI was
// found (MVR_HAVE_MPI); without mpirun the program never initialises MPI.
//
// Collective calls must be reached by every rank in the same order, so a
// rank never leaves a phase by an exception: each phase catches its error
// and the ranks agree on the outcome (agree) before going on.
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <thread>
#include <vector>

namespace mvr::app {

class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  // The session of this process, or null outside an MPI job.
  static MpiSession* current();

  int rank() const { return rank_; }
  int ranks() const { return ranks_; }
  // Starts MPI if it has not started (on a thread of its own) and waits
  // until it is initialised; every call below does. Call it where no
  // other thread reads the environment (MPI_Init writes it).
  void ready();

  // Whether the ranks have agreed once (agree): until then an error that
  // reaches main is a set-up error the other ranks are waiting to hear of.
  bool agreedOnce() const { return agreedOnce_; }
  // Collective: whether every rank's phase succeeded. When some failed,
  // the lowest failing rank prints its error (one line for the job, the
  // same one every rank would print for a shared cause like a bad scene).
  bool agree(const std::string& error);
  // Collective: every rank's strings, in rank order, on rank 0 (empty
  // elsewhere).
  std::vector<std::string> gatherAtRoot(const std::vector<std::string>& mine);
  // Collective: the largest of every rank's value, on every rank.
  double maxOf(double value);
  void barrier();

 private:
  void start();
  void shareTheCores();
  int rank_ = 0, ranks_ = 1;
  bool agreedOnce_ = false;
  std::thread mpi_;  // MPI's main thread: initialises, then finalises
  std::once_flag started_;
  std::mutex mutex_;
  std::condition_variable changed_;
  int mpiRank_ = 0, mpiRanks_ = 1;  // MPI's, set by its thread
  bool initialised_ = false, finishing_ = false;
};

// A phase ended because another rank failed; it printed the error.
struct JobFailed {};

// A file every rank of the job reads and writes at offsets of its own
// (MPI-IO, so a parallel file system serves it): where EPIs of one rank
// meet the views another encodes, or the output itself (a stream's records).
// Opened and closed collectively.
class SharedFile {
 public:
  enum class Lifetime { Scratch, Kept };  // Scratch: removed on close; Kept: truncated at open
  // Collective. Throws naming the path when it cannot be created.
  explicit SharedFile(const std::string& path, Lifetime lifetime = Lifetime::Scratch);
  ~SharedFile();  // collective
  SharedFile(const SharedFile&) = delete;
  SharedFile& operator=(const SharedFile&) = delete;

  void write(uint64_t offset, std::span<const std::byte> bytes);
  void read(uint64_t offset, std::span<std::byte> bytes);

 private:
  struct Handle;
  std::string path_;
  std::unique_ptr<Handle> handle_;
};

}  // namespace mvr::app
