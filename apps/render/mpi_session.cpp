#include "apps/render/mpi_session.h"

#include <mpi.h>

#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <thread>

#include "apps/cli/job_split.h"
#include "mvr/error.h"
#include "mvr/parallel.h"

namespace mvr::app {
namespace {

MpiSession* g_session = nullptr;

// MPI counts are ints: large transfers go in pieces.
constexpr uint64_t kPiece = uint64_t(1) << 30;

}  // namespace

// MPI_Init sets many environment variables, and setenv reallocates the
// environment under any thread reading it (Mesa's EGL start-up crashed in
// getenv when MPI started beside it): MPI starts when the first call needs
// it, with the start-up's threads done. By then every rank has started, so
// its wait on the launcher is short. It runs on a thread of its own, MPI's
// main thread, which also finalises; the others call MPI one at a time
// (MPI_THREAD_SERIALIZED). The rank and the ranks on this machine are the
// launcher's environment's until then.
MpiSession::MpiSession(int&, char**&) {
  g_session = this;
  if (const int rank = launchedRank(); rank >= 0) {
    rank_ = rank, ranks_ = launchedRanks();
  } else {
    ready();
    rank_ = mpiRank_, ranks_ = mpiRanks_;
  }
  shareTheCores();
}

void MpiSession::start() {
  mpi_ = std::thread([this] {
#ifdef OPEN_MPI
    // The ranks exchange only agreements and names (frames meet in MPI-IO
    // files), so Open MPI's probe of every messaging layer for the fastest
    // (0.2 s of a 0.23 s MPI_Init here, its cm and ucx layers) buys nothing:
    // ob1 runs over any transport (shared memory, TCP, InfiniBand). A PML
    // the job names (mpirun --mca pml) is kept.
    setenv("OMPI_MCA_pml", "ob1", 0);
#endif
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_SERIALIZED, &provided);
    // Errors come back as codes and are reported as this program's own.
    MPI_Comm_set_errhandler(MPI_COMM_WORLD, MPI_ERRORS_RETURN);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    std::unique_lock lock(mutex_);
    mpiRank_ = rank, mpiRanks_ = ranks, initialised_ = true;
    changed_.notify_all();
    changed_.wait(lock, [this] { return finishing_; });
    lock.unlock();
    MPI_Finalize();
  });
}

void MpiSession::ready() {
  std::call_once(started_, [this] { start(); });
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return initialised_; });
}

// Ranks on one machine divide its cores (unless --threads says otherwise),
// and so does llvmpipe's rasterizer: K ranks of all-core pools would run K
// times as many threads as cores.
void MpiSession::shareTheCores() {
  int local = launchedLocalRanks();
  if (local < 1) {
    ready();
    MPI_Comm node;
    MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
    MPI_Comm_size(node, &local);
    MPI_Comm_free(&node);
  }
  // mpirun binds each rank to its cores where it can (then the affinity
  // says how many); unbound ranks divide the machine.
  const int threads = std::max(1, std::min(availableCores(), int(std::thread::hardware_concurrency()) / local));
  setThreadCount(threads);
  setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 0);
}

MpiSession::~MpiSession() {
  ready();
  {
    std::lock_guard lock(mutex_);
    finishing_ = true;
  }
  changed_.notify_all();
  mpi_.join();
  g_session = nullptr;
}

MpiSession* MpiSession::current() { return g_session; }

bool MpiSession::agree(const std::string& error) {
  ready();
  const int mine = error.empty() ? ranks_ : rank_;
  int first = ranks_;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  agreedOnce_ = true;
  if (first == rank_) std::fprintf(stderr, "mvr: %s\n", error.c_str());
  return first == ranks_;
}

std::vector<std::string> MpiSession::gatherAtRoot(const std::vector<std::string>& mine) {
  ready();
  std::string joined;
  for (const std::string& s : mine) joined += s + '\n';
  const int length = int(joined.size());
  std::vector<int> lengths(static_cast<size_t>(ranks_), 0), offsets(static_cast<size_t>(ranks_), 0);
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  long total = 0;
  for (int k = 0; k < ranks_; ++k) {
    offsets[size_t(k)] = int(total);
    total += lengths[size_t(k)];
  }
  if (rank_ == 0 && total > std::numeric_limits<int>::max()) fail("mpi", "too many names to gather");
  std::string all(rank_ == 0 ? size_t(total) : 0, '\0');
  MPI_Gatherv(joined.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR, 0,
              MPI_COMM_WORLD);
  std::vector<std::string> out;
  for (size_t start = 0, end; (end = all.find('\n', start)) != std::string::npos; start = end + 1)
    out.push_back(all.substr(start, end - start));
  return out;
}

double MpiSession::maxOf(double value) {
  ready();
  double out = value;
  MPI_Allreduce(&value, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return out;
}

void MpiSession::barrier() {
  ready();
  MPI_Barrier(MPI_COMM_WORLD);
}

struct SharedFile::Handle {
  MPI_File file = MPI_FILE_NULL;
};

SharedFile::SharedFile(const std::string& path, Lifetime lifetime)
    : path_(path), handle_(std::make_unique<Handle>()) {
  MpiSession::current()->ready();
  const bool scratch = lifetime == Lifetime::Scratch;
  const int rc = MPI_File_open(MPI_COMM_WORLD, path.c_str(),
                               MPI_MODE_CREATE | MPI_MODE_RDWR | (scratch ? MPI_MODE_DELETE_ON_CLOSE : 0),
                               MPI_INFO_NULL, &handle_->file);
  if (rc != MPI_SUCCESS) fail(path, scratch ? "cannot create the job's shared scratch file" : "cannot create file");
  MPI_File_set_errhandler(handle_->file, MPI_ERRORS_RETURN);
  // A file left by an earlier job would keep its bytes past this one's end.
  if (!scratch && MPI_File_set_size(handle_->file, 0) != MPI_SUCCESS) fail(path, "cannot truncate file");
}

SharedFile::~SharedFile() {
  if (handle_->file != MPI_FILE_NULL) MPI_File_close(&handle_->file);
}

void SharedFile::write(uint64_t offset, std::span<const std::byte> bytes) {
  for (uint64_t done = 0; done < bytes.size();) {
    const int n = int(std::min<uint64_t>(kPiece, bytes.size() - done));
    MPI_Status status;
    if (MPI_File_write_at(handle_->file, MPI_Offset(offset + done), bytes.data() + done, n, MPI_BYTE, &status) !=
        MPI_SUCCESS)
      fail(path_, "cannot write the job's shared file (is the disk full?)");
    done += uint64_t(n);
  }
}

void SharedFile::read(uint64_t offset, std::span<std::byte> bytes) {
  for (uint64_t done = 0; done < bytes.size();) {
    const int n = int(std::min<uint64_t>(kPiece, bytes.size() - done));
    MPI_Status status;
    int got = 0;
    if (MPI_File_read_at(handle_->file, MPI_Offset(offset + done), bytes.data() + done, n, MPI_BYTE, &status) !=
            MPI_SUCCESS ||
        MPI_Get_count(&status, MPI_BYTE, &got) != MPI_SUCCESS || got != n)
      fail(path_, "cannot read back the job's shared file");
    done += uint64_t(n);
  }
}

}  // namespace mvr::app
