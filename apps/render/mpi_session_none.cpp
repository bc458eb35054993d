// The MPI session where MPI was not found at build time: no process is
// ever part of a job, and starting one under mpirun is an error.
#include "apps/render/mpi_session.h"

#include "mvr/error.h"

namespace mvr::app {

MpiSession::MpiSession(int&, char**&) {
  fail("mpirun", "this mvr was built without MPI (scripts/setup installs Open MPI; rebuild)");
}
MpiSession::~MpiSession() = default;
void MpiSession::ready() {}
MpiSession* MpiSession::current() { return nullptr; }
bool MpiSession::agree(const std::string&) { return true; }
std::vector<std::string> MpiSession::gatherAtRoot(const std::vector<std::string>& mine) { return mine; }
double MpiSession::maxOf(double value) { return value; }
void MpiSession::barrier() {}

struct SharedFile::Handle {};
SharedFile::SharedFile(const std::string& path, Lifetime) { fail(path, "a shared scratch file needs MPI"); }
SharedFile::~SharedFile() = default;
void SharedFile::write(uint64_t, std::span<const std::byte>) {}
void SharedFile::read(uint64_t, std::span<std::byte>) {}

}  // namespace mvr::app
