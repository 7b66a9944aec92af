#include "freed_memory.hpp"

#include <cstddef>
#include <mutex>
#include <string>
#include <vector>

#if __has_include(<dlfcn.h>)
#include <dlfcn.h>
#endif

namespace vesselmesh {

namespace {

using Mallctl = int (*)(const char*, void*, std::size_t*, void*, std::size_t);

/// jemalloc's control function, when the process's allocator exports it.
Mallctl mallctl() {
#if __has_include(<dlfcn.h>)
  static const Mallctl found = reinterpret_cast<Mallctl>(dlsym(RTLD_DEFAULT, "mallctl"));
  return found;
#else
  return nullptr;
#endif
}

/// An arena's decay times (ms; -1: never purge), as they were before the first hold.
struct Decay {
  unsigned arena;
  std::ptrdiff_t dirty, muzzy;
};

std::mutex hold_mutex;
int holds = 0;
std::vector<Decay> saved;

/// jemalloc's name for an arena's decay time; `which` is "dirty" or "muzzy".
std::string decay_name(unsigned arena, const char* which) {
  return "arena." + std::to_string(arena) + "." + which + "_decay_ms";
}

bool read_decay(unsigned arena, const char* which, std::ptrdiff_t& value) {
  std::size_t size = sizeof value;
  return mallctl()(decay_name(arena, which).c_str(), &value, &size, nullptr, 0) == 0;
}

void write_decay(unsigned arena, const char* which, std::ptrdiff_t value) {
  mallctl()(decay_name(arena, which).c_str(), nullptr, nullptr, &value, sizeof value);
}

void keep_freed_pages() {
  unsigned arenas = 0;
  std::size_t size = sizeof arenas;
  if (mallctl()("arenas.narenas", &arenas, &size, nullptr, 0) != 0) return;
  for (unsigned a = 0; a < arenas; ++a) {
    Decay d{a, 0, 0};
    // Arenas not yet created have no decay to read; they start with the process's defaults.
    if (!read_decay(a, "dirty", d.dirty) || !read_decay(a, "muzzy", d.muzzy)) continue;
    saved.push_back(d);
    write_decay(a, "dirty", -1);
    write_decay(a, "muzzy", -1);
  }
}

void restore_decay() {
  for (const Decay& d : saved) {
    write_decay(d.arena, "dirty", d.dirty);
    write_decay(d.arena, "muzzy", d.muzzy);
  }
  saved.clear();
}

}  // namespace

bool FreedMemoryHold::supported() { return mallctl() != nullptr; }

FreedMemoryHold::FreedMemoryHold() {
  if (!supported()) return;
  const std::lock_guard<std::mutex> lock(hold_mutex);
  if (holds++ == 0) keep_freed_pages();
  held_ = true;
}

FreedMemoryHold::~FreedMemoryHold() { release(); }

void FreedMemoryHold::release() {
  if (!held_) return;
  const std::lock_guard<std::mutex> lock(hold_mutex);
  held_ = false;
  if (--holds == 0) restore_decay();
}

}  // namespace vesselmesh
