#pragma once
// What this process has used so far, for stats.json (Linux getrusage).
#include <malloc.h>
#include <sys/resource.h>

#include <cstddef>

namespace dsswarm {

inline std::size_t peak_rss_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::size_t>(usage.ru_maxrss) * 1024;  // Linux reports KiB
}

// User + system CPU time of every thread of the process.
inline double cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

// Hands the heap's free pages back to the system (glibc keeps them, per
// thread arena, for reuse). Called between phases that allocate differently,
// e.g. after SLAM and before the outputs are built, so that the peak is the
// larger phase's and not the sum of what both left behind.
inline void release_free_heap() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

}  // namespace dsswarm
