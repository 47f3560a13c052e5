#include "ugs/mechanics/collective.hpp"

#include <new>
#include <stdexcept>

#include "ugs/formats/error.hpp"

namespace ugs::mech {

void broadcast(MPI_Comm comm, std::string& s, int root) {
  unsigned long long n = s.size();
  MPI_Bcast(&n, 1, MPI_UNSIGNED_LONG_LONG, root, comm);
  s.resize(n);
  if (n) MPI_Bcast(s.data(), static_cast<int>(n), MPI_CHAR, root, comm);
}

void collective(MPI_Comm comm, const std::function<void()>& work) {
  int kind = 0;  // 0 ok, 1 compute, 2 input, 3 out of memory, 4 other
  std::string message, where;
  try {
    work();
  } catch (const InputError& e) {
    kind = 2, message = e.what(), where = e.where();
  } catch (const ComputeError& e) {
    kind = 1, message = e.what();
  } catch (const std::bad_alloc&) {
    kind = 3, message = "out of memory";
  } catch (const std::exception& e) {
    kind = 4, message = e.what();
  }
  int size = 1, rank = 0;
  MPI_Comm_size(comm, &size);
  MPI_Comm_rank(comm, &rank);
  int mine = kind ? rank : size, first = size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size) return;
  MPI_Bcast(&kind, 1, MPI_INT, first, comm);
  broadcast(comm, message, first);
  if (kind == 2) {
    // InputError's text already holds "where: message"; keep it whole.
    throw InputError("", message);
  }
  if (kind == 3) throw std::bad_alloc();
  if (kind == 4) throw std::runtime_error(message);
  throw ComputeError(message);
}

}  // namespace ugs::mech
