# The engine's layering, checked on its sources (a test: cmake -DENGINE_DIR=... -P include_rules.cmake):
#   engine/         includes no Qt and no OpenGL header (it builds and runs without either);
#   model/          the cloth model both solvers share: includes only core/ of the engine;
#   collision/      geometry only (distances, BVHs, CCD, proximity): includes no solver header (newton/, pd/);
#   pd/             the preview: includes no header of newton/, the drape.
# A violation prints FILE:LINE: the include and the rule, and fails.
cmake_minimum_required(VERSION 3.20)
if(NOT ENGINE_DIR)
  message(FATAL_ERROR "usage: cmake -DENGINE_DIR=<repo>/engine -P include_rules.cmake")
endif()

set(violations 0)
# check(<glob root> <regex of forbidden includes> <rule text>)
function(check root forbidden rule)
  file(GLOB_RECURSE files "${ENGINE_DIR}/${root}/*.h" "${ENGINE_DIR}/${root}/*.cpp")
  foreach(file IN LISTS files)
    file(STRINGS "${file}" lines REGEX "^[ \t]*#[ \t]*include")
    foreach(line IN LISTS lines)
      if(line MATCHES "${forbidden}")
        file(RELATIVE_PATH relative "${ENGINE_DIR}/.." "${file}")
        message("${relative}: ${line}: ${rule}")
        math(EXPR count "${violations} + 1")
        set(violations ${count} PARENT_SCOPE)
      endif()
    endforeach()
  endforeach()
endfunction()

check("" "[<\"](Qt[A-Za-z]*/|Q[A-Z][A-Za-z]*>|GL/|GLES[0-9]*/|EGL/|epoxy/)" "engine/ includes no Qt or OpenGL header")
check("include/drape/model" "\"drape/(avatar|collision|fabric|garment|geometry|io|newton|pattern|pd|scene|sim)/" "model/ includes only core/")
check("src/model" "\"drape/(avatar|collision|fabric|garment|geometry|io|newton|pattern|pd|scene|sim)/" "model/ includes only core/")
check("include/drape/collision" "\"drape/(newton|pd|sim)/" "collision/ is geometry only: no solver header")
check("src/collision" "\"drape/(newton|pd|sim)/" "collision/ is geometry only: no solver header")
check("include/drape/pd" "\"drape/newton/" "pd/ includes no newton/ header")
check("src/pd" "\"drape/newton/" "pd/ includes no newton/ header")

if(violations GREATER 0)
  message(FATAL_ERROR "${violations} include(s) break the engine's layering")
endif()
message("the engine's includes follow its layering")
