# Python bindings (python/): cffi in ABI mode over libbiref.so. The build turns the public headers
# into the plain declarations cffi reads (biref_cdef.h: preprocessed, system headers stubbed out),
# installs them with the package, and runs the pytest suite with Debian's own interpreter.
set(BIREF_CDEF ${CMAKE_CURRENT_BINARY_DIR}/python/biref_cdef.h)
set(BIREF_CDEF_STUBS ${CMAKE_CURRENT_BINARY_DIR}/python/stub_include)
foreach(h stddef.h stdint.h stdio.h complex.h)
  # cffi knows size_t, uint32_t, uint8_t and FILE itself.
  file(WRITE ${BIREF_CDEF_STUBS}/${h}.in "/* stub for cffi declarations */\n")
  configure_file(${BIREF_CDEF_STUBS}/${h}.in ${BIREF_CDEF_STUBS}/${h} COPYONLY)
endforeach()
file(GLOB BIREF_PUBLIC_HEADERS CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/include/biref/*.h)
add_custom_command(
  OUTPUT ${BIREF_CDEF}
  COMMAND ${CMAKE_C_COMPILER} -E -P -nostdinc -I${BIREF_CDEF_STUBS} -I${CMAKE_CURRENT_SOURCE_DIR}/include
          -DBIREF_API= -DBIREF_EXPERIMENTAL_API ${CMAKE_CURRENT_SOURCE_DIR}/include/biref/biref.h -o ${BIREF_CDEF}
  DEPENDS ${BIREF_PUBLIC_HEADERS}
  COMMENT "Declarations for the Python bindings")
add_custom_target(biref_python_cdef ALL DEPENDS ${BIREF_CDEF})

# Debian's interpreter sees python3-numpy/cffi/pytest; another python3 first on PATH may not.
if(NOT DEFINED BIREF_PYTHON)
  if(EXISTS /usr/bin/python3)
    set(BIREF_PYTHON /usr/bin/python3)
  else()
    find_program(BIREF_PYTHON python3)
  endif()
endif()

if(BIREF_INSTALL AND TARGET biref_shared)
  if(NOT BIREF_PYTHON_INSTALL_DIR AND BIREF_PYTHON)
    execute_process(COMMAND ${BIREF_PYTHON} -c "import sys; print('%d.%d' % sys.version_info[:2])"
                    OUTPUT_VARIABLE BIREF_PYTHON_VERSION OUTPUT_STRIP_TRAILING_WHITESPACE ERROR_QUIET)
    # Debian's python3 searches <prefix>/lib/python3.X/dist-packages (not site-packages).
    if(EXISTS /usr/lib/python3/dist-packages)
      set(BIREF_PYTHON_SITE dist-packages)
    else()
      set(BIREF_PYTHON_SITE site-packages)
    endif()
    if(BIREF_PYTHON_VERSION)
      set(BIREF_PYTHON_INSTALL_DIR lib/python${BIREF_PYTHON_VERSION}/${BIREF_PYTHON_SITE})
    endif()
  endif()
  set(BIREF_PYTHON_INSTALL_DIR "${BIREF_PYTHON_INSTALL_DIR}" CACHE STRING
      "Where `cmake --install` puts the Python package, relative to the prefix (empty: not installed)")
  install(FILES ${BIREF_CDEF} DESTINATION ${BIREF_INSTALL_DATADIR})
  if(BIREF_PYTHON_INSTALL_DIR)
    file(RELATIVE_PATH BIREF_PY_TO_LIB /prefix/${BIREF_PYTHON_INSTALL_DIR}/biref
         /prefix/${CMAKE_INSTALL_LIBDIR}/libbiref.so.${BIREF_SOVERSION})
    file(RELATIVE_PATH BIREF_PY_TO_CDEF /prefix/${BIREF_PYTHON_INSTALL_DIR}/biref
         /prefix/${BIREF_INSTALL_DATADIR}/biref_cdef.h)
    file(WRITE ${CMAKE_CURRENT_BINARY_DIR}/python/_install_paths.py.in
         "# Written by the CMake install: where libbiref and its declarations are, relative to this package.\n"
         "LIBRARY = \"${BIREF_PY_TO_LIB}\"\nCDEF = \"${BIREF_PY_TO_CDEF}\"\n")
    configure_file(${CMAKE_CURRENT_BINARY_DIR}/python/_install_paths.py.in
                   ${CMAKE_CURRENT_BINARY_DIR}/python/_install_paths.py COPYONLY)
    install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/python/biref DESTINATION ${BIREF_PYTHON_INSTALL_DIR}
            FILES_MATCHING PATTERN "*.py" PATTERN "__pycache__" EXCLUDE)
    install(FILES ${CMAKE_CURRENT_BINARY_DIR}/python/_install_paths.py
            DESTINATION ${BIREF_PYTHON_INSTALL_DIR}/biref)
  endif()
endif()

if(BIREF_BUILD_TESTS AND TARGET biref_shared AND TARGET biref_cli AND NOT BIREF_SANITIZE AND BIREF_PYTHON)
  execute_process(COMMAND ${BIREF_PYTHON} -c "import numpy, cffi, pytest" RESULT_VARIABLE BIREF_PY_DEPS
                  OUTPUT_QUIET ERROR_QUIET)
  if(BIREF_PY_DEPS EQUAL 0)
    add_test(NAME python_bindings
             COMMAND ${BIREF_PYTHON} -m pytest -q -p no:cacheprovider ${CMAKE_CURRENT_SOURCE_DIR}/python/tests
             WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
    set_tests_properties(python_bindings PROPERTIES ENVIRONMENT
      "BIREF_LIBRARY=$<TARGET_FILE:biref_shared>;BIREF_CDEF=${BIREF_CDEF};BIREF_CLI=$<TARGET_FILE:biref_cli>;PYTHONPATH=${CMAKE_CURRENT_SOURCE_DIR}/python;PYTHONDONTWRITEBYTECODE=1")
  else()
    message(WARNING "python3-numpy, python3-cffi or python3-pytest missing for ${BIREF_PYTHON}: "
                    "the Python bindings are not tested (scripts/install-deps.sh installs them)")
  endif()
endif()
