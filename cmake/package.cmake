# `cmake --install build --prefix P` and `cpack -G DEB` (docs/install.md, "Installing on cluster nodes").
#   P/bin/simbob
#   P/lib/simbob/libsimbob_video.so   the module opened on demand (FFmpeg)
#   P/share/simbob/scenes/     the example scenes with the parts they import and the meshes they read
#   P/share/simbob/scripts/simbob_client.py   the peer socket_robot.xml starts (../scripts/)
#   P/share/simbob/python/simbob_client.py and P/share/simbob/examples/clients/: the client libraries
#   P/share/doc/simbob/README.md and P/share/doc/simbob/docs/ (the reference README links to)
#   P/lib/python3/dist-packages/simbob/   the Python package, when it is built (docs/python.md)
# The .deb installs under /usr; its Depends comes from dpkg-shlibdeps over the binary, so it
# names Debian's runtime library packages (libode8, libcairo2, ...) and never a -dev package:
# `apt install ./simbob_*.deb` on a Debian 12 node pulls exactly those.
include(GNUInstallDirs)
install(TARGETS simbob RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# Opened by the binary as ../lib/simbob/libsimbob_video.so when it writes a video.
install(TARGETS simbob_video LIBRARY DESTINATION lib/simbob)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/scenes/ DESTINATION ${CMAKE_INSTALL_DATADIR}/simbob/scenes)
install(PROGRAMS ${PROJECT_SOURCE_DIR}/scripts/simbob_client.py DESTINATION ${CMAKE_INSTALL_DATADIR}/simbob/scripts)
install(FILES ${PROJECT_SOURCE_DIR}/python/simbob_client.py DESTINATION ${CMAKE_INSTALL_DATADIR}/simbob/python)
install(DIRECTORY ${PROJECT_SOURCE_DIR}/examples/clients/ DESTINATION ${CMAKE_INSTALL_DATADIR}/simbob/examples/clients)
install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR}/docs)
# The Python package (`import simbob`) where Debian's /usr/bin/python3 finds it:
# P/lib/python3/dist-packages/simbob/ (the compiled _simbob*.so and python/simbob/*.py).
if(SIMBOB_PYTHON_BUILT)
  set(SIMBOB_PYTHON_INSTALL_DIR lib/python3/dist-packages/simbob)
  install(TARGETS simbob_python LIBRARY DESTINATION ${SIMBOB_PYTHON_INSTALL_DIR})
  install(FILES ${SIMBOB_PYTHON_SOURCES} DESTINATION ${SIMBOB_PYTHON_INSTALL_DIR})
endif()

set(CPACK_GENERATOR "DEB")
set(CPACK_PACKAGE_NAME "simbob")
set(CPACK_PACKAGE_VENDOR "simbob")
set(CPACK_PACKAGE_CONTACT "simbob maintainers <simbob@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "headless batch simulator for mobile robots (Simulator Bob scenes on ODE)")
set(CPACK_PACKAGE_DESCRIPTION
    "simbob runs Simulator Bob XML scenes on the Open Dynamics Engine without a display and\n writes pose trajectories, run summaries and plots; it runs parameter sweeps one case per\n Slurm array task. The example scenes are in /usr/share/simbob/scenes.")
set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")
# The RelWithDebInfo binary carries its debug information; the package does not need it.
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # simbob_0.1.0_amd64.deb
set(CPACK_DEBIAN_PACKAGE_SECTION "science")
set(CPACK_DEBIAN_PACKAGE_PRIORITY "optional")
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# Opened with dlopen only when recording (lib/render), so not in the shlibs Depends.
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libegl-mesa0, libgl1-mesa-dri, libosmesa6")
# `simbob view` reads three.js from Debian's libjs-three at run time (lib/view): appended to the
# shlibs Depends.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libjs-three")
# The Python module is built for one interpreter version (its file name carries the ABI tag) and
# needs numpy. Recommended, not required: a cluster node that runs the CLI needs no Python.
if(SIMBOB_PYTHON_BUILT)
  math(EXPR simbob_python_next "${Python3_VERSION_MINOR} + 1")
  set(CPACK_DEBIAN_PACKAGE_RECOMMENDS
      "${CPACK_DEBIAN_PACKAGE_RECOMMENDS}, python3 (>= ${Python3_VERSION_MAJOR}.${Python3_VERSION_MINOR}~), python3 (<< ${Python3_VERSION_MAJOR}.${simbob_python_next}), python3-numpy")
endif()
include(CPack)
