#pragma once
// API: internal (may change without notice; the library's own threading over oneTBB)
// The library's fork-join parallelism, in one place: oneTBB's parallel_for and parallel_invoke.
//
// Under ThreadSanitizer (CI builds the suite with it) the fork and the join are annotated as
// the happens-before edges they are: Debian's libtbb is not built with ThreadSanitizer, which
// therefore cannot see the synchronization of its scheduler and would report every value one
// parallel loop writes and the code after it reads. Tasks stay unordered among themselves, so a
// race between two iterations or two branches is still reported.
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#if defined(__SANITIZE_THREAD__)
extern "C" void __tsan_acquire(void* address);
extern "C" void __tsan_release(void* address);
#endif

namespace ibl {

namespace detail {
// The edges of one fork-join: what precedes the fork happens before each task (a task acquires
// `fork`), each task happens before what follows the join (a task releases `join`).
struct ForkJoin {
#if defined(__SANITIZE_THREAD__)
  char forkToken = 0, joinToken = 0;
  // `tasks` must be complete before the release: the compiler may not sink their stores past
  // it, as the empty asm reads them.
  void fork(const void* tasks) {
    asm volatile("" : : "r"(tasks) : "memory");
    __tsan_release(&forkToken);
  }
  void taskBegins() {
    __tsan_acquire(&forkToken);
  }
  void taskEnds() {
    __tsan_release(&joinToken);
  }
  void joined() {
    __tsan_acquire(&joinToken);
  }
#else
  void fork(const void*) {}
  void taskBegins() {}
  void taskEnds() {}
  void joined() {}
#endif
};
}  // namespace detail

// body(i) for every i in [begin, end), on all cores, in any order.
template <typename Index, typename Body>
void parallelFor(Index begin, Index end, const Body& body) {
  detail::ForkJoin edges;
  const auto task = [&](Index i) {
    edges.taskBegins();
    body(i);
    edges.taskEnds();
  };
  edges.fork(&task);  // after the task exists: its captures are read before taskBegins
  tbb::parallel_for(begin, end, task);
  edges.joined();
}

// f() and g(), possibly at the same time.
template <typename F, typename G>
void parallelInvoke(const F& f, const G& g) {
  detail::ForkJoin edges;
  const auto task = [&](const auto& work) {
    edges.taskBegins();
    work();
    edges.taskEnds();
  };
  const auto first = [&] { task(f); };
  const auto second = [&] { task(g); };
  edges.fork(&first);  // after the tasks exist: their captures are read before taskBegins
  edges.fork(&second);
  tbb::parallel_invoke(first, second);
  edges.joined();
}

}  // namespace ibl
