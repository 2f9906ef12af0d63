# mpirun end to end: 1, 2 and 3 ranks of one thread each give the image a
# single process gives, bit for bit, for path, bdpt and lt; a rank that fails
# ends the job with its message and a non-zero exit, in bounded time.
set(ENV{OMPI_ALLOW_RUN_AS_ROOT} 1)
set(ENV{OMPI_ALLOW_RUN_AS_ROOT_CONFIRM} 1)
set(ENV{OMPI_MCA_btl} "self,vader")  # one machine: shared memory only
# Under the sanitizers: Open MPI's plug-ins keep allocations to the end
# that LeakSanitizer reports (in modules it cannot name); leaks of
# Lantern's own are the other tests' to find, memory errors still fail here.
if(DEFINED ENV{ASAN_OPTIONS})
  set(ENV{ASAN_OPTIONS} "$ENV{ASAN_OPTIONS}:detect_leaks=0")
endif()
set(mpirun ${MPIEXEC} --oversubscribe --bind-to none)
set(base render ${SRC}/scenes/lantern.pbrt --spp 24 --resolution 40 30 --quiet)
foreach(integrator path bdpt lt)
  execute_process(COMMAND ${LANTERN} ${base} --integrator ${integrator} -o ${OUT}/mpi-single.exr
                  RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 120)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "single process ${integrator}: exit ${rc}\n${err}")
  endif()
  foreach(ranks 1 2 3)
    file(REMOVE ${OUT}/mpi-ranks.exr)
    execute_process(COMMAND ${mpirun} -np ${ranks} ${LANTERN} ${base} --integrator ${integrator} --threads 1
                            -o ${OUT}/mpi-ranks.exr
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
    execute_process(COMMAND ${LANTERN} compare ${OUT}/mpi-ranks.exr ${OUT}/mpi-single.exr OUTPUT_VARIABLE cmp)
    if(NOT rc EQUAL 0 OR NOT cmp MATCHES "^mse 0\n")
      message(FATAL_ERROR "${ranks} ranks, ${integrator}: exit ${rc}, against one process:\n${cmp}${out}${err}")
    endif()
  endforeach()
endforeach()

# A scene only rank 0 cannot read would leave the others waiting: the job
# must end with the error and a non-zero status instead.
execute_process(COMMAND ${mpirun} -np 2 ${LANTERN} render ${OUT}/no-such-scene.pbrt -o ${OUT}/x.exr
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(rc EQUAL 0 OR NOT "${out}${err}" MATCHES "cannot open scene file" OR NOT "${out}${err}" MATCHES "ending all ranks")
  message(FATAL_ERROR "failing ranks: exit ${rc}\n${out}${err}")
endif()
# What is not supported across ranks yet is refused by name.
execute_process(COMMAND ${mpirun} -np 2 ${LANTERN} ${base} --part 1/2 -o ${OUT}/x.film
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 60)
if(rc EQUAL 0 OR NOT "${out}${err}" MATCHES "--part cannot be used with several MPI ranks")
  message(FATAL_ERROR "--part under mpirun: exit ${rc}\n${out}${err}")
endif()
message(STATUS "mpi end-to-end: all checks passed")
