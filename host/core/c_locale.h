#pragma once
// The "C" locale for the calling thread while a CLocaleScope lives (POSIX uselocale): numbers are
// then formatted and parsed with a decimal point in Lua (tostring, string.format, tonumber, the -D
// values it converts) and in the C library, whatever locale the process set. The CLI never sets
// one; a Python process may: after locale.setlocale(LC_ALL, "de_DE.UTF-8") a scene's
// "tex_" .. 0.5 named 'tex_0,5.tif' and -D x=0,5 arrived as the number 0.5 (the reproducibility
// trial of 2026-11-29). Scopes nest; each restores the thread's locale it found.
#include <locale.h>

namespace dicsynth {

class CLocaleScope {
 public:
  CLocaleScope() {
    // Made once, never freed: a locale object every thread may use.
    static const locale_t c = newlocale(LC_ALL_MASK, "C", locale_t(nullptr));
    if (c != locale_t(nullptr)) previous_ = uselocale(c);
  }
  ~CLocaleScope() {
    if (previous_ != locale_t(nullptr)) uselocale(previous_);
  }
  CLocaleScope(const CLocaleScope&) = delete;
  CLocaleScope& operator=(const CLocaleScope&) = delete;

 private:
  locale_t previous_ = locale_t(nullptr);
};

}  // namespace dicsynth
