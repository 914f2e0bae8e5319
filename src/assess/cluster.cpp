#include "assess/cluster.hpp"

#include <cstdlib>
#include <stdexcept>

#ifdef J232_HAVE_MPI
#include <mpi.h>
#endif

namespace j232::assess::cluster {

namespace {
int g_rank = 0, g_size = 1;
#ifdef J232_HAVE_MPI
bool g_joined = false;

// Launched by mpirun/mpiexec (Open MPI, MPICH, Slurm's PMI)?
bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK", "MPI_LOCALNRANKS"})
    if (std::getenv(v)) return true;
  return false;
}
#endif
}  // namespace

bool available() {
#ifdef J232_HAVE_MPI
  return true;
#else
  return false;
#endif
}

void init(int* argc, char*** argv) {
#ifdef J232_HAVE_MPI
  if (!launched_by_mpi()) return;
  int provided = 0;
  // Only the main thread calls MPI; oneTBB's workers never do.
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &g_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &g_size);
  g_joined = true;
#else
  (void)argc, (void)argv;
#endif
}

void finalize() {
#ifdef J232_HAVE_MPI
  if (g_joined) MPI_Finalize();
  g_joined = false;
#endif
}

void abort(int code) {
#ifdef J232_HAVE_MPI
  if (g_joined && g_size > 1) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::_Exit(code);
}

int rank() { return g_rank; }
int size() { return g_size; }

#ifdef J232_HAVE_MPI
namespace {
// Messages may exceed an int's count of bytes: sent in pieces of at most 1 GiB.
constexpr std::size_t kPiece = std::size_t{1} << 30;
void check(int status, const char* what) {
  if (status != MPI_SUCCESS) throw std::runtime_error(std::string("MPI ") + what + " failed");
}
}  // namespace

void send(int to, const std::string& bytes) {
  unsigned long long n = bytes.size();
  check(MPI_Send(&n, 1, MPI_UNSIGNED_LONG_LONG, to, 0, MPI_COMM_WORLD), "send");
  for (std::size_t at = 0; at < bytes.size(); at += kPiece)
    check(MPI_Send(bytes.data() + at, static_cast<int>(std::min(kPiece, bytes.size() - at)), MPI_BYTE, to, 1, MPI_COMM_WORLD), "send");
}

std::string receive(int from) {
  unsigned long long n = 0;
  check(MPI_Recv(&n, 1, MPI_UNSIGNED_LONG_LONG, from, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "receive");
  std::string bytes(n, '\0');
  for (std::size_t at = 0; at < bytes.size(); at += kPiece)
    check(MPI_Recv(bytes.data() + at, static_cast<int>(std::min(kPiece, bytes.size() - at)), MPI_BYTE, from, 1, MPI_COMM_WORLD,
                   MPI_STATUS_IGNORE),
          "receive");
  return bytes;
}

void broadcast_from_writer(std::string& bytes) {
  unsigned long long n = bytes.size();
  check(MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, 0, MPI_COMM_WORLD), "broadcast");
  bytes.resize(n);
  for (std::size_t at = 0; at < bytes.size(); at += kPiece)
    check(MPI_Bcast(bytes.data() + at, static_cast<int>(std::min(kPiece, bytes.size() - at)), MPI_BYTE, 0, MPI_COMM_WORLD), "broadcast");
}
#else
void send(int, const std::string&) { throw std::logic_error("j232 was built without MPI"); }
std::string receive(int) { throw std::logic_error("j232 was built without MPI"); }
void broadcast_from_writer(std::string&) {}
#endif

}  // namespace j232::assess::cluster
