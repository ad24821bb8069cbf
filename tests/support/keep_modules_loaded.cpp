// Linked into every executable of a leak-checked (ASan/LSan) build, and only there: see
// cmake/sanitizers.cmake. GL drivers (Mesa's EGL vendor library, the dri/gallium driver) leak a
// few bytes by design and are loaded and unloaded again while EGL probes platforms and devices.
// LeakSanitizer names modules only at exit, so a leak made by an unloaded driver shows up as
// `<unknown module>` and no name suppression in tests/lsan.supp can match it; which modules get
// unloaded depends on the machine's EGL platforms and devices. Making dlclose a no-op keeps every
// module mapped until exit: its leaks carry its name (suppressed), its globals stay roots, and
// leaks in rtsph's own code are still reported (tests/support/lsan_reports_own_leak.sh checks).
// ASan does not intercept dlclose; the executable's definition wins symbol lookup for every
// library (the link exports it: --export-dynamic-symbol).

extern "C" int dlclose(void* /*handle*/) { return 0; }
