# Run by CPack on the .deb it made (CPACK_POST_BUILD_SCRIPTS, cmake/package.cmake).
# CPack runs ldconfig from a postrm it writes for any library under /usr/lib,
# and a package with a postrm stays behind in dpkg's "rc" state after
# `apt remove` (dpkg keeps the script for a purge). Debian's way, as
# dh_makeshlibs does it, is a trigger: the postrm goes, DEBIAN/triggers asks
# dpkg to run ldconfig after installing and after removing.
foreach(deb IN LISTS CPACK_PACKAGE_FILES)
  set(dir ${deb}.tree)
  file(REMOVE_RECURSE ${dir})
  execute_process(COMMAND dpkg-deb -R ${deb} ${dir} COMMAND_ERROR_IS_FATAL ANY)
  file(REMOVE ${dir}/DEBIAN/postrm)
  file(WRITE ${dir}/DEBIAN/triggers "activate-noawait ldconfig\n")
  execute_process(COMMAND dpkg-deb --root-owner-group -b ${dir} ${deb} OUTPUT_QUIET COMMAND_ERROR_IS_FATAL ANY)
  file(REMOVE_RECURSE ${dir})
endforeach()
