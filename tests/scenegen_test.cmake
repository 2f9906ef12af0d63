# lantern-scenegen's forest at a small size must load, report its
# instances, and render with bdpt without a non-finite sample.
file(REMOVE_RECURSE ${OUT})
execute_process(COMMAND ${GEN} ${OUT} --instanced-triangles 2e5 --unique-triangles 1e5 RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "lantern-scenegen failed: ${rc}\n${out}")
endif()
execute_process(COMMAND ${LANTERN} render ${OUT}/scene.pbrt --spp 1 --resolution 64 36 --quiet --stats ${OUT}/s.json
                        -o ${OUT}/forest.exr RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 300)
file(READ ${OUT}/s.json stats)
string(JSON instances GET "${stats}" scene_contents instances)
string(JSON traced GET "${stats}" scene_contents instanced_triangles)
string(JSON nonfinite GET "${stats}" nonfinite_samples)
if(NOT rc EQUAL 0 OR instances LESS 20 OR traced LESS 300000 OR NOT nonfinite EQUAL 0)
  message(FATAL_ERROR "forest: exit ${rc}, ${instances} instances, ${traced} traced triangles, ${nonfinite} non-finite\n${err}")
endif()
message(STATUS "scenegen smoke: ${instances} instances, ${traced} triangles traced")
