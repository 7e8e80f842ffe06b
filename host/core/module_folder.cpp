#include "core/module_folder.h"

#include <dlfcn.h>
#include <elf.h>
#include <link.h>

#include <cstdint>

#include "core/hex.h"

namespace dicsynth {

std::filesystem::path codeFolder() {
  // dladdr names the file this function was loaded from: the executable, or the Python module a
  // Python process loaded (where /proc/self/exe would name python3).
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&codeFolder), &info) != 0 && info.dli_fname != nullptr) {
    std::error_code ec;
    const std::filesystem::path file = std::filesystem::canonical(info.dli_fname, ec);
    if (!ec) return file.parent_path();
  }
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path(".") : exe.parent_path();
}

namespace {

struct BuildIdSearch {
  std::uintptr_t address = 0;  // an address inside the binary wanted
  std::string id;
};

// dl_iterate_phdr's callback: in the object one of whose loaded segments holds `address`, the
// NT_GNU_BUILD_ID note of its PT_NOTE segments.
int findBuildId(dl_phdr_info* info, std::size_t, void* data) {
  auto* search = static_cast<BuildIdSearch*>(data);
  bool holds = false;
  for (int i = 0; i < info->dlpi_phnum; ++i) {
    const ElfW(Phdr)& ph = info->dlpi_phdr[i];
    const std::uintptr_t start = info->dlpi_addr + ph.p_vaddr;
    holds |= ph.p_type == PT_LOAD && search->address >= start && search->address < start + ph.p_memsz;
  }
  if (!holds) return 0;
  for (int i = 0; i < info->dlpi_phnum; ++i) {
    const ElfW(Phdr)& ph = info->dlpi_phdr[i];
    if (ph.p_type != PT_NOTE) continue;
    const auto* p = reinterpret_cast<const unsigned char*>(info->dlpi_addr + ph.p_vaddr);
    const unsigned char* end = p + ph.p_memsz;
    while (p + sizeof(ElfW(Nhdr)) <= end) {
      const auto* note = reinterpret_cast<const ElfW(Nhdr)*>(p);
      const unsigned char* name = p + sizeof(ElfW(Nhdr));
      const unsigned char* desc = name + ((note->n_namesz + 3) & ~3u);
      if (note->n_type == NT_GNU_BUILD_ID && note->n_namesz == 4 && desc + note->n_descsz <= end) {
        search->id = hexString({desc, note->n_descsz});
        return 1;
      }
      p = desc + ((note->n_descsz + 3) & ~3u);
    }
  }
  return 1;  // the binary, without a build ID
}

}  // namespace

std::string codeBuildId() {
  static const std::string id = [] {
    BuildIdSearch search;
    search.address = reinterpret_cast<std::uintptr_t>(&codeBuildId);
    dl_iterate_phdr(findBuildId, &search);
    return search.id;
  }();
  return id;
}

std::string codeBuildIdText() {
  const std::string id = codeBuildId();
  return id.empty() ? "none" : id;
}

void* LoadableModule::symbol(const char* name, std::string& failure) {
  std::call_once(once_, [this] {
    path_ = (codeFolder() / fileName_).string();
    handle_ = dlopen(path_.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle_) {
      const char* e = dlerror();
      loadFailure_ = "cannot load " + path_ + " (" + (e ? e : "unknown reason") + ")";
    }
  });
  if (!handle_) {
    failure = loadFailure_;
    return nullptr;
  }
  void* function = dlsym(handle_, name);
  if (!function) failure = path_ + " lacks " + name + " (a stale build?)";
  return function;
}

}  // namespace dicsynth
