# Stages the three.js modules that `luxel bake --html` puts in its page (apps/luxel/html_page.cpp)
# into the build tree, where apps/luxel/html_page_assets.cpp includes them in the luxel binary
# (.incbin). Run at configure time and by the target luxel-html-viewer-assets at every build:
#   cmake -DTHREE=SOURCE_TREE/tools/three-check/node_modules/three -DDEST=BUILD/html-viewer -P stage_three.cmake
# Each module is copied only when it changed (so nothing recompiles otherwise). A module missing
# from THREE (tools/three-check/node_modules not installed) is staged empty: the build still
# succeeds, and `luxel bake --html` fails naming the file and scripts/install-deps.sh. Installing
# it later and rebuilding is enough: no re-configure.
# Keep the list in step with kThreeModules in apps/luxel/html_page_assets.cpp.
set(modules
  build/three.module.js
  build/three.core.js
  examples/jsm/loaders/GLTFLoader.js
  examples/jsm/utils/BufferGeometryUtils.js
  examples/jsm/utils/SkeletonUtils.js
  examples/jsm/controls/OrbitControls.js)
foreach(m ${modules})
  set(dest "${DEST}/three/${m}")
  if(EXISTS "${THREE}/${m}")
    get_filename_component(dir "${dest}" DIRECTORY)
    file(MAKE_DIRECTORY "${dir}")
    file(COPY_FILE "${THREE}/${m}" "${dest}" ONLY_IF_DIFFERENT)
  elseif(NOT EXISTS "${dest}")
    file(WRITE "${dest}" "")
  else()
    file(SIZE "${dest}" size)
    if(size GREATER 0)
      file(WRITE "${dest}" "")
    endif()
  endif()
endforeach()
