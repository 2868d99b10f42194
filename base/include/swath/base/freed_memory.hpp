#pragma once
// How a swath program's allocator keeps the memory it frees.

#include <cstddef>

namespace swath::base {

/// Keeps memory the program frees for its next allocations instead of handing it back to the
/// operating system at once. Call once, at the start of a program (every swath executable does,
/// and the split and division benches, which time what the executables run).
///
/// Why: planning repeats the same work for ~100 candidate lane directions, each allocating and
/// freeing buffers of 0.1–4 MB (a 10,000-vertex outline's edges, coverage samples). With glibc's
/// default thresholds each such buffer comes as fresh pages from the kernel and goes back when
/// freed: 20,000 page faults for one plan of a 10,000-vertex field (6,500 with this), and a whole
/// process 0.70 against 0.53 s on a virtual machine (bench/split_bench.cpp, --default_allocator).
/// With glibc: blocks below 32 MiB come from the heap (M_MMAP_THRESHOLD), and the heap's free top
/// is returned only beyond 256 MiB (M_TRIM_THRESHOLD), so a process holds at most its peak plus
/// that per malloc arena (one per thread at most). Heaps grow 16 MiB of address space at a time
/// (M_TOP_PAD), so that growing one costs a system call per 16 MiB, not one per few pages; the
/// pages become resident only when used. Elsewhere it does nothing.
void keep_freed_memory();

/// Asks the kernel for transparent huge pages (2 MiB) under the next 30 MiB the calling thread
/// allocates, and under the same on each thread parallel_for() starts from then on. Call after
/// keep_freed_memory(), where a process is about to plan (swath plan; each area of swath batch).
///
/// Why: a plan of a traced outline touches 6-8 MB of fresh heap, ~1,500 of its ~2,100 page
/// faults, ~1.9 us each on the virtual machine measured (docs/performance.md, "Huge pages").
/// With 2 MiB pages the same memory comes in a few faults. It takes effect where the kernel gives
/// huge pages to memory marked for them (`madvise` in
/// /sys/kernel/mm/transparent_hugepage/enabled, Debian's default) and changes nothing where it
/// gives them always or never; where no huge page is at hand the kernel gives small ones, as
/// without. SWATH_HUGE_PAGES=0 in the environment switches it off. Elsewhere than glibc on Linux
/// it does nothing.
void heap_on_huge_pages();

/// parallel_for()'s threads call this first: their heap marked as heap_on_huge_pages() marks the
/// caller's, once that was called.
void thread_heap_started();

/// The process's resident memory (bytes, from /proc/self/statm); 0 where it cannot be read.
std::size_t resident_bytes();

/// Hands the memory the program has freed back to the operating system (glibc's malloc_trim: the
/// free pages of every arena, not only a heap's top) when the process's resident memory is above
/// `limit_bytes`; true when it did. For a process that plans area after area (swath batch's
/// workers): keep_freed_memory() would keep its largest area's memory, up to 256 MiB of free heap
/// and its fragments, until it ends. Elsewhere it does nothing (false).
bool give_back_freed_memory(std::size_t limit_bytes);

}  // namespace swath::base
