#pragma once
// Keeping freed memory while the core works, for processes that allocate with jemalloc (Blender does).
// jemalloc hands the pages of large freed blocks back to the system at once (it purges its arena for
// blocks of 8 MiB and more eagerly), so each of the core's big arrays starts on fresh pages, and a page
// fault per 4 KiB makes the core about twice as slow as under glibc's malloc, which keeps them. While
// held, every arena keeps its freed pages for reuse; on release each gets its own decay times back and
// purges what it kept. Elsewhere (no `mallctl` in the process) holding does nothing.

namespace vesselmesh {

/// Counted: the first hold makes the arenas keep freed pages, the last release restores them.
class FreedMemoryHold {
 public:
  FreedMemoryHold();
  ~FreedMemoryHold();
  FreedMemoryHold(const FreedMemoryHold&) = delete;
  FreedMemoryHold& operator=(const FreedMemoryHold&) = delete;
  /// Releases early (the destructor then does nothing).
  void release();
  /// Whether the process's allocator is one that holding changes.
  static bool supported();

 private:
  bool held_ = false;
};

}  // namespace vesselmesh
