#------------------------------------------------------------------------------
# Import Debian's OpenFOAM v1912 libraries (no SONAME, so by full path) with
# the headers unpacked by bin/installDependencies into ThirdParty/.
# Provides the interface target OpenFOAM::OpenFOAM.
#------------------------------------------------------------------------------

set(FOAM_SRC "${PROJECT_SOURCE_DIR}/ThirdParty/openfoam-1912/src")
if(NOT EXISTS "${FOAM_SRC}/OpenFOAM/lnInclude/argList.H")
    message(FATAL_ERROR "OpenFOAM v1912 headers not found in ${FOAM_SRC}: "
        "run bin/installDependencies")
endif()

function(spem_import_foam_lib name)
    find_library(FOAM_LIB_${name} NAMES ${name} PATHS /usr/lib NO_DEFAULT_PATH)
    if(NOT FOAM_LIB_${name})
        message(FATAL_ERROR "lib${name}.so from Debian's openfoam not found")
    endif()
    add_library(OpenFOAM::lib${name} SHARED IMPORTED)
    set_target_properties(OpenFOAM::lib${name} PROPERTIES
        IMPORTED_LOCATION "${FOAM_LIB_${name}}"
        IMPORTED_NO_SONAME TRUE)
endfunction()

spem_import_foam_lib(OpenFOAM)
spem_import_foam_lib(Pstream)

add_library(OpenFOAM_OpenFOAM INTERFACE)
add_library(OpenFOAM::OpenFOAM ALIAS OpenFOAM_OpenFOAM)
target_include_directories(OpenFOAM_OpenFOAM SYSTEM INTERFACE
    "${FOAM_SRC}/OpenFOAM/lnInclude"
    "${FOAM_SRC}/OSspecific/POSIX/lnInclude")
# Definitions matching Debian's build of v1912 (double precision, 32-bit
# labels, templates compiled from headers)
target_compile_definitions(OpenFOAM_OpenFOAM INTERFACE
    WM_DP WM_LABEL_SIZE=32 NoRepository OPENFOAM=1912)
# --no-as-needed: a library that only registers models in a run-time
# selection table must stay linked (Debian's gcc links --as-needed). Pstream
# must be named explicitly (wmake hides this).
target_link_libraries(OpenFOAM_OpenFOAM INTERFACE
    -Wl,--no-as-needed OpenFOAM::libOpenFOAM OpenFOAM::libPstream ${CMAKE_DL_LIBS})
