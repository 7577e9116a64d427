/* Linked into every executable of a sanitizer build (-DDRAPE_SANITIZE=ON) only: dlclose leaves each shared library
 * loaded. LeakSanitizer reports at exit and names an allocation's library from the libraries loaded then; Mesa's
 * drivers and Qt's plugins, unloaded before that, would show as "<unknown module>" and miss their suppressions in
 * scripts/sanitize.supp. The unwinder stays the fast one: the full one deadlocks in llvmpipe's JIT (its frame
 * registration allocates while libgcc holds the unwinder's lock). */
int dlclose(void *handle) {
  (void)handle;
  return 0;
}
