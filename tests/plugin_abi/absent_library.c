/* The shared library libfilmback_filter_nolibrary.so depends on. It is built where the dynamic
 * loader never looks and the plugin carries no run path to it, so loading the plugin fails the
 * way it does when a plugin's dependency is not installed (tests/plugin_abi/CMakeLists.txt). */
int fb_test_absent_function(void);

int fb_test_absent_function(void) {
  return 0;
}
