# End-to-end checks of the lantern command: a render writes its image, bad
# input exits non-zero with file:line:column, SIGINT writes what was rendered,
# the bidirectional integrators and `lantern compare` run.
function(expect_run)
  cmake_parse_arguments(E "" "EXIT;MATCH;NAME" "ARGS" ${ARGN})
  execute_process(COMMAND ${LANTERN} ${E_ARGS} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
  if(NOT rc STREQUAL E_EXIT)
    message(FATAL_ERROR "${E_NAME}: exit code ${rc}, expected ${E_EXIT}\n${out}${err}")
  endif()
  if(E_MATCH AND NOT "${out}${err}" MATCHES "${E_MATCH}")
    message(FATAL_ERROR "${E_NAME}: output does not match '${E_MATCH}':\n${out}${err}")
  endif()
endfunction()

file(REMOVE ${OUT}/cli.exr ${OUT}/cli.png)
expect_run(NAME render-exr EXIT 0 ARGS render ${SRC}/scenes/cornell-box.pbrt --spp 2 --resolution 32 32 -o ${OUT}/cli.exr)
expect_run(NAME render-png EXIT 0 ARGS render ${SRC}/scenes/cornell-box.pbrt --spp 1 --resolution 16 16 --quiet -o ${OUT}/cli.png)
foreach(f cli.exr cli.png)
  if(NOT EXISTS ${OUT}/${f})
    message(FATAL_ERROR "render did not write ${f}")
  endif()
endforeach()
expect_run(NAME help EXIT 0 MATCH "--spp" ARGS render --help)
# A figure can be reproduced from its files: the image header and the stats
# name the program, the machine, the command and every setting.
expect_run(NAME provenance-header EXIT 0 MATCH "lantern:commit [0-9a-f]+.*lantern:maxdepth.*lantern:sampler zsobol"
           ARGS info ${OUT}/cli.exr)
expect_run(NAME provenance-stats EXIT 0 ARGS render ${SRC}/scenes/cornell-box.pbrt --spp 1 --resolution 8 8 --quiet
           --stats ${OUT}/provenance.json -o ${OUT}/provenance.exr)
file(READ ${OUT}/provenance.json stats)
foreach(key "\"commit\"" "\"cpu\"" "\"command\"" "\"maxdepth\"" "\"budget\": \"spp 1\"" "\"seed\"")
  string(FIND "${stats}" "${key}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "provenance-stats: ${key} missing from the stats:\n${stats}")
  endif()
endforeach()
# Usage errors exit with 2 (docs/cli.md) and name the near miss.
expect_run(NAME version EXIT 0 MATCH "^lantern [0-9]+\\.[0-9]+\\.[0-9]+ \\(commit [0-9a-f]+" ARGS --version)
expect_run(NAME flag-near-miss EXIT 2 MATCH "did you mean \"--spp\"" ARGS render ${SRC}/scenes/cornell-box.pbrt --sp 16)
expect_run(NAME command-near-miss EXIT 2 MATCH "did you mean \"render\"" ARGS rendr ${SRC}/scenes/cornell-box.pbrt)
expect_run(NAME negative-seed EXIT 2 MATCH "--seed: must be an integer of 0 or more" ARGS render ${SRC}/scenes/cornell-box.pbrt --seed -1)
expect_run(NAME target-error-part EXIT 1 MATCH "target error .*not with --part"
           ARGS render ${SRC}/scenes/cornell-box.pbrt --integrator vcm --target-error 0.01 --part 1/2 --resolution 8 8
           -o ${OUT}/x.part)
expect_run(NAME missing-scene EXIT 2 MATCH "cannot open scene file" ARGS render ${OUT}/no-such-scene.pbrt -o ${OUT}/x.png)
file(WRITE ${OUT}/broken.pbrt "WorldBegin\nShape \"sphere\" \"float radius\" [ 1\n")
expect_run(NAME syntax-error EXIT 2 MATCH "broken.pbrt:2:.*error: .*missing" ARGS render ${OUT}/broken.pbrt -o ${OUT}/x.png)
# Bad values say what was expected, in words (no numeric range spelt out).
expect_run(NAME bad-flag EXIT 2 MATCH "--spp: must be a positive integer, not \"-3\"" ARGS render ${SRC}/scenes/cornell-box.pbrt --spp -3)
expect_run(NAME bad-time EXIT 2 MATCH "--time: must be a positive number of seconds" ARGS render ${SRC}/scenes/cornell-box.pbrt --time -1)
expect_run(NAME bad-threads EXIT 2 MATCH "--threads: must be a positive integer, not \"abc\"" ARGS render ${SRC}/scenes/cornell-box.pbrt --threads abc)
expect_run(NAME bad-resolution EXIT 2 MATCH "--resolution: must be an integer from 1 to 65536" ARGS render ${SRC}/scenes/cornell-box.pbrt --resolution 0 5)
expect_run(NAME bad-maxdepth EXIT 2 MATCH "--maxdepth: must be an integer of 0 or more" ARGS render ${SRC}/scenes/cornell-box.pbrt --maxdepth -2)

# Output files are checked before anything renders: these would run for
# hours (and time out here) if the check came at the end.
expect_run(NAME output-folder-missing EXIT 1 MATCH "the folder \"[^\"]*no-such-dir\" does not exist"
           ARGS render ${SRC}/scenes/cornell-box.pbrt --spp 100000 -o ${OUT}/no-such-dir/x.exr)
expect_run(NAME output-format-unknown EXIT 1 MATCH "no image writer for the extension \".xyz\""
           ARGS render ${SRC}/scenes/cornell-box.pbrt --spp 100000 -o ${OUT}/x.xyz)
expect_run(NAME trace-folder-missing EXIT 1 MATCH "cannot write the trace"
           ARGS render ${SRC}/scenes/cornell-box.pbrt --spp 100000 --trace ${OUT}/no-such-dir/t.json -o ${OUT}/x.exr)
expect_run(NAME checkpoint-folder-missing EXIT 1 MATCH "cannot write the checkpoint"
           ARGS render ${SRC}/scenes/cornell-box.pbrt --spp 100000 --checkpoint 60 --checkpoint-file ${OUT}/no-such-dir/c.ckpt -o ${OUT}/x.exr)
# A folder removed during the render: the image goes to a rescue copy in
# the working directory, and the exit status says something went wrong.
file(REMOVE_RECURSE ${OUT}/vanishing)
file(REMOVE ${OUT}/x.rescue.exr)
file(MAKE_DIRECTORY ${OUT}/vanishing)
execute_process(COMMAND sh -c "${LANTERN} render ${SRC}/scenes/cornell-box.pbrt --spp 100000 --resolution 32 32 --threads 1 --quiet -o ${OUT}/vanishing/x.exr & pid=$!; sleep 2; rm -rf ${OUT}/vanishing; kill -INT $pid; wait $pid"
                WORKING_DIRECTORY ${OUT} RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
if(NOT rc EQUAL 1 OR NOT EXISTS ${OUT}/x.rescue.exr OR NOT err MATCHES "saved instead in")
  message(FATAL_ERROR "removed output folder: exit ${rc}, rescue copy ${OUT}/x.rescue.exr\n${err}")
endif()

# The bidirectional integrators, per-strategy images, and compare.
file(REMOVE_RECURSE ${OUT}/strategies)
expect_run(NAME bdpt EXIT 0 MATCH "light extension" ARGS render ${SRC}/scenes/cornell-box.pbrt --integrator bdpt --spp 2
           --resolution 16 16 --maxdepth 2 --strategies ${OUT}/strategies -o ${OUT}/bdpt.exr)
foreach(f s0_t2_weighted.exr s1_t1_unweighted.exr s2_t2_weighted.exr s3_t1_unweighted.exr)
  if(NOT EXISTS ${OUT}/strategies/${f})
    message(FATAL_ERROR "--strategies did not write ${f}")
  endif()
endforeach()
expect_run(NAME lt EXIT 0 ARGS render ${SRC}/scenes/cornell-box.pbrt --integrator lt --spp 2 --resolution 16 16 --quiet
           -o ${OUT}/lt.exr)
expect_run(NAME strategies-need-bdpt EXIT 1 MATCH "need --integrator bdpt" ARGS render ${SRC}/scenes/cornell-box.pbrt
           --integrator path --spp 1 --resolution 8 8 --strategies ${OUT}/strategies -o ${OUT}/x.exr)
expect_run(NAME compare EXIT 0 MATCH "relmse [0-9.e+-]+\nmae" ARGS compare ${OUT}/lt.exr ${OUT}/bdpt.exr)
expect_run(NAME compare-size-mismatch EXIT 1 MATCH "sizes differ" ARGS compare ${OUT}/cli.exr ${OUT}/bdpt.exr)
# Outputs that are not plain files are written through, never renamed over:
# standard output as "-" or /dev/stdout (which stays a link), and a link
# to a file (the link stays, the file it names gets the statistics, and an
# image through a link likewise).
expect_run(NAME stats-dash EXIT 0 MATCH "\"integrator\": \"path\"" ARGS render ${SRC}/scenes/cornell-box.pbrt --spp 1
           --resolution 8 8 --quiet -o ${OUT}/dash.exr --stats -)
if(EXISTS ${OUT}/-)
  message(FATAL_ERROR "--stats - wrote a file named -")
endif()
expect_run(NAME stats-dev-stdout EXIT 0 MATCH "\"integrator\": \"path\"" ARGS render ${SRC}/scenes/cornell-box.pbrt
           --spp 1 --resolution 8 8 --quiet -o ${OUT}/dash.exr --stats /dev/stdout)
if(NOT IS_SYMLINK /dev/stdout)
  message(FATAL_ERROR "--stats /dev/stdout replaced the link /dev/stdout")
endif()
file(REMOVE ${OUT}/linked-stats.json ${OUT}/stats-link.json ${OUT}/linked.exr ${OUT}/image-link.exr)
file(CREATE_LINK linked-stats.json ${OUT}/stats-link.json SYMBOLIC)
file(CREATE_LINK linked.exr ${OUT}/image-link.exr SYMBOLIC)
expect_run(NAME stats-through-link EXIT 0 ARGS render ${SRC}/scenes/cornell-box.pbrt --spp 1 --resolution 8 8 --quiet
           -o ${OUT}/image-link.exr --stats ${OUT}/stats-link.json)
foreach(link stats-link.json image-link.exr)
  if(NOT IS_SYMLINK ${OUT}/${link})
    message(FATAL_ERROR "writing through ${link} replaced the link with a file")
  endif()
endforeach()
file(READ ${OUT}/linked-stats.json linked_stats)
if(NOT linked_stats MATCHES "\"integrator\": \"path\"" OR NOT EXISTS ${OUT}/linked.exr)
  message(FATAL_ERROR "the files the links name were not written")
endif()
# An 8-bit PNG is sRGB-encoded: compared with the EXR of the same render
# (no value above 1 to clip) its means agree within 8-bit quantisation.
# Read as linear, they were 1.6-2.8 times too bright.
foreach(ext exr png)
  expect_run(NAME formats-${ext} EXIT 0 ARGS render ${SRC}/tests/conformance/image-formats.pbrt --spp 2 --quiet
             -o ${OUT}/formats.${ext})
endforeach()
expect_run(NAME compare-png-with-exr EXIT 0 MATCH "ratio (0\\.99[5-9]|1\\.00[0-4])[0-9]* (0\\.99[5-9]|1\\.00[0-4])[0-9]* (0\\.99[5-9]|1\\.00[0-4])"
           ARGS compare ${OUT}/formats.png ${OUT}/formats.exr)
expect_run(NAME bad-mis EXIT 2 ARGS render ${SRC}/scenes/cornell-box.pbrt --mis nonsense)
# The path tracer's roulette scale: 0.01 to 100, nan refused as a usage error;
# the image's header names it.
expect_run(NAME bad-roulette EXIT 2 MATCH "--roulette: Value nan not in range" ARGS render ${SRC}/scenes/cornell-box.pbrt --roulette nan)
expect_run(NAME roulette-render EXIT 0 ARGS render ${SRC}/scenes/cornell-box.pbrt --roulette 3 --spp 1 --resolution 8 8
           --quiet -o ${OUT}/roulette.exr)
expect_run(NAME roulette-header EXIT 0 MATCH "lantern:roulette 3" ARGS info ${OUT}/roulette.exr)
# Paths per camera sample: 1, 2, 4, 8 or 16, anything else a usage error; the
# image's header names it, and a time budget renders with it.
expect_run(NAME bad-split EXIT 2 MATCH "--split: 3 not in" ARGS render ${SRC}/scenes/cornell-box.pbrt --split 3)
expect_run(NAME bad-light-choice EXIT 2 MATCH "--light-choice: bvh not in" ARGS render ${SRC}/scenes/cornell-box.pbrt
           --light-choice bvh)
# --guide-stop: auto or never, anything else a usage error; a guided render's
# stats say whether its guide stopped (on the Cornell box the lobes, the
# default, do not pay: their records leave 0.93 of the BSDF's second moment
# in the third iteration at this size, and they stop after it), and never
# goes on to the end. The header names the distribution.
expect_run(NAME bad-guide-stop EXIT 2 MATCH "--guide-stop: maybe not in" ARGS render ${SRC}/scenes/cornell-box.pbrt
           --guide --guide-stop maybe)
expect_run(NAME guide-stop-stats EXIT 0 MATCH "\"stopped_after\": 2" ARGS render ${SRC}/scenes/cornell-box.pbrt
           --guide --spp 32 --seed 1 --resolution 64 48 --quiet -o ${OUT}/guide-stop.exr --stats -)
expect_run(NAME guide-stop-never EXIT 0 MATCH "\"stopped_after\": -1" ARGS render ${SRC}/scenes/cornell-box.pbrt
           --guide --guide-stop never --spp 32 --seed 1 --resolution 64 48 --quiet -o ${OUT}/guide-kept.exr --stats -)
expect_run(NAME guide-stop-header EXIT 0 MATCH "lantern:guide-stop never" ARGS info ${OUT}/guide-kept.exr)
expect_run(NAME guide-distribution-header EXIT 0 MATCH "lantern:guide-distribution vmm" ARGS info ${OUT}/guide-stop.exr)
# The prism's pilot gives light subpaths another choice than power, and says so
# (under a time budget: a render of a few samples is too small for a pilot).
expect_run(NAME light-choice-stats EXIT 0 MATCH "\"light_choice\": {[^}]*\"chosen\": \"(measured|mixed|uniform)\""
           ARGS render ${SRC}/scenes/prism.pbrt --integrator bdpt --time 0.1 --resolution 48 36 --quiet -o ${OUT}/prism.exr
           --stats -)
expect_run(NAME split-timed EXIT 0 ARGS render ${SRC}/scenes/cornell-box.pbrt --split 4 --time 0.3 --resolution 16 16
           --quiet -o ${OUT}/split.exr)
expect_run(NAME split-header EXIT 0 MATCH "lantern:split 4" ARGS info ${OUT}/split.exr)
# bdpt's light subpath rate: auto, 0 or 0.01 to 1, anything else a usage error;
# the header says what was asked for.
expect_run(NAME bad-light-subpaths EXIT 2 MATCH "expected auto, 0 or a number from 0.01 to 1" ARGS render
           ${SRC}/scenes/cornell-box.pbrt --integrator bdpt --light-subpaths 0.005)
# vcm's merge pilot: auto or on, anything else a usage error.
expect_run(NAME bad-merging EXIT 2 MATCH "off not in \\{auto,on\\}" ARGS render ${SRC}/scenes/cornell-box.pbrt
           --integrator vcm --merging off)
# 0, the eye subpaths alone: the path tracer renders them, and the header
# says so; refused, with the reason, where a spot light's light needs light
# subpaths.
expect_run(NAME light-subpaths-zero-render EXIT 0 ARGS render ${SRC}/scenes/cornell-box.pbrt --integrator bdpt
           --light-subpaths 0 --spp 1 --resolution 8 8 --quiet -o ${OUT}/light-subpaths-zero.exr)
expect_run(NAME light-subpaths-zero-header EXIT 0 MATCH "lantern:light_subpath_rate 0([^.0-9]|$)" ARGS info
           ${OUT}/light-subpaths-zero.exr)
expect_run(NAME light-subpaths-zero-refused EXIT 1 MATCH "the scene has a spot light and a dielectric" ARGS render
           ${SRC}/scenes/prism.pbrt --integrator bdpt --light-subpaths 0 --spp 1 --resolution 8 8 -o
           ${OUT}/light-subpaths-refused.exr)
expect_run(NAME light-subpaths-render EXIT 0 ARGS render ${SRC}/scenes/cornell-box.pbrt --integrator bdpt --light-subpaths 0.5
           --spp 1 --resolution 8 8 --quiet -o ${OUT}/light-subpaths.exr)
expect_run(NAME light-subpaths-header EXIT 0 MATCH "lantern:light_subpaths 0.5" ARGS info ${OUT}/light-subpaths.exr)
# Under auto the header also says which rate the pilot chose (under a time
# budget: a render of a few samples is too small for the pilot).
expect_run(NAME light-subpaths-auto-render EXIT 0 ARGS render ${SRC}/scenes/cornell-box.pbrt --integrator bdpt --time 0.2
           --resolution 16 16 --quiet -o ${OUT}/light-subpaths-auto.exr)
expect_run(NAME light-subpaths-auto-header EXIT 0 MATCH "lantern:light_subpath_rate (1|0.5|0.25|0.125|0)" ARGS info
           ${OUT}/light-subpaths-auto.exr)
# A render of fewer than 16 times the pilot's samples runs no pilot, and says so.
expect_run(NAME light-subpaths-no-pilot EXIT 0 MATCH "light subpaths: 1 per camera sample \\(--light-subpaths auto\\): the render is too small"
           ARGS render ${SRC}/scenes/cornell-box.pbrt --integrator bdpt --spp 8 --resolution 16 16 -o ${OUT}/light-subpaths-small.exr)

# SIGINT during a long render: exit 130 and an image with the samples so far,
# for the path tracer and for bdpt (whose splats go through the same merge).
# With --trace, the timeline of the waves that ran is written too.
foreach(integrator path bdpt)
  file(REMOVE ${OUT}/interrupted.exr ${OUT}/interrupted.json)
  execute_process(COMMAND sh -c "${LANTERN} render ${SRC}/scenes/cornell-box.pbrt --integrator ${integrator} --spp 100000 --resolution 64 64 --threads 1 --quiet --trace ${OUT}/interrupted.json --trace-waves 50 -o ${OUT}/interrupted.exr & pid=$!; sleep 2; kill -INT $pid; wait $pid"
                  RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 60)
  if(NOT rc EQUAL 130 OR NOT EXISTS ${OUT}/interrupted.exr OR NOT EXISTS ${OUT}/interrupted.json)
    message(FATAL_ERROR "SIGINT (${integrator}): exit ${rc}, image and trace written: ${OUT}/interrupted.exr, .json\n${err}")
  endif()
  file(READ ${OUT}/interrupted.json trace)
  string(JSON events ERROR_VARIABLE json_error LENGTH "${trace}" traceEvents)
  if(json_error OR events LESS 10)
    message(FATAL_ERROR "SIGINT (${integrator}): the trace does not parse or is empty: ${json_error}")
  endif()
endforeach()
# SIGTERM, then SIGINT, each writing the image so far (its header giving the
# true sample count) and a checkpoint; --resume then finishes the render,
# which must equal a straight one exactly. Each signal is sent once the run
# has written a checkpoint of its own, so a slow start (a loaded machine)
# cannot make it arrive before the render began.
set(ck_spp 1500)
set(ck_args render ${SRC}/scenes/cornell-box.pbrt --integrator bdpt --spp ${ck_spp} --resolution 24 24 --quiet)
string(JOIN " " ck_line ${ck_args})
file(REMOVE ${OUT}/straight.exr ${OUT}/stopped.exr ${OUT}/stopped.exr.ckpt)
execute_process(COMMAND ${LANTERN} ${ck_args} -o ${OUT}/straight.exr RESULT_VARIABLE rc TIMEOUT 300)
foreach(step "--checkpoint 0.1;TERM" "--checkpoint 0.1 --resume --threads 1;INT")
  list(GET step 0 flags)
  list(GET step 1 signal)
  execute_process(COMMAND sh -c "touch ${OUT}/marker; ${LANTERN} ${ck_line} -o ${OUT}/stopped.exr ${flags} 2>&1 & pid=$!; i=0; while [ $i -lt 1200 ] && [ -z \"$(find ${OUT}/stopped.exr.ckpt -newer ${OUT}/marker 2>/dev/null)\" ]; do sleep 0.05; i=$((i+1)); done; kill -${signal} $pid; wait $pid"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out TIMEOUT 300)
  if(NOT rc EQUAL 130 OR NOT EXISTS ${OUT}/stopped.exr.ckpt)
    message(FATAL_ERROR "SIG${signal} with ${flags}: exit ${rc}, checkpoint ${OUT}/stopped.exr.ckpt\n${out}")
  endif()
  string(REGEX MATCH "wrote the ([0-9]+) samples" _ "${out}")
  set(told ${CMAKE_MATCH_1})
  execute_process(COMMAND ${LANTERN} info ${OUT}/stopped.exr OUTPUT_VARIABLE info)
  string(REGEX MATCH "lantern:samples ([0-9]+)" _ "${info}")
  if(NOT "${told}" STREQUAL "${CMAKE_MATCH_1}" OR "${told}" STREQUAL "" OR NOT info MATCHES "interrupted true")
    message(FATAL_ERROR "SIG${signal}: the message says ${told} samples, the image header says:\n${info}")
  endif()
endforeach()
execute_process(COMMAND ${LANTERN} ${ck_args} -o ${OUT}/stopped.exr --resume RESULT_VARIABLE rc ERROR_VARIABLE err TIMEOUT 300)
execute_process(COMMAND ${LANTERN} compare ${OUT}/stopped.exr ${OUT}/straight.exr OUTPUT_VARIABLE cmp)
if(NOT rc EQUAL 0 OR NOT cmp MATCHES "^mse 0\n" OR EXISTS ${OUT}/stopped.exr.ckpt)
  message(FATAL_ERROR "resume: exit ${rc}, comparison with the straight render:\n${cmp}${err}")
endif()
expect_run(NAME resume-nothing EXIT 2 MATCH "nothing to resume" ARGS ${ck_args} -o ${OUT}/stopped.exr --resume)

# A render in parts (--part K/N) merged into the image the single render
# makes, bit for bit (each part runs bdpt's pilots and chooses as the single
# render does: 256 spp is enough for them); merge refuses a missing part
# unless asked for a preview.
set(pt_args render ${SRC}/scenes/cornell-box.pbrt --integrator bdpt --spp 256 --resolution 24 24 --quiet)
execute_process(COMMAND ${LANTERN} ${pt_args} -o ${OUT}/whole.exr RESULT_VARIABLE rc)
foreach(k 1 2 3)
  expect_run(NAME part-${k} EXIT 0 ARGS ${pt_args} --part ${k}/3 -o ${OUT}/part${k}.film --threads ${k})
endforeach()
expect_run(NAME merge EXIT 0 ARGS merge ${OUT}/part2.film ${OUT}/part3.film ${OUT}/part1.film -o ${OUT}/merged.exr)
execute_process(COMMAND ${LANTERN} compare ${OUT}/merged.exr ${OUT}/whole.exr OUTPUT_VARIABLE cmp)
if(NOT cmp MATCHES "^mse 0\n")
  message(FATAL_ERROR "merged parts differ from the single render:\n${cmp}")
endif()
expect_run(NAME merge-missing EXIT 1 MATCH "part 2/3 is missing; merge the parts there are with --preview"
           ARGS merge ${OUT}/part1.film ${OUT}/part3.film -o ${OUT}/merged.exr)
expect_run(NAME merge-preview EXIT 0 MATCH "warning: preview: part 2/3 is missing"
           ARGS merge ${OUT}/part1.film ${OUT}/part3.film -o ${OUT}/preview.exr --preview)
# A part of another scene (here the same box with another name and bytes)
# is refused, naming the scene line that differs.
file(READ ${SRC}/scenes/cornell-box.pbrt box)
file(WRITE ${OUT}/other-box.pbrt "${box}\n# edited\n")
expect_run(NAME part-other-scene EXIT 0 ARGS render ${OUT}/other-box.pbrt --integrator bdpt --spp 32 --resolution 24 24
           --quiet --part 2/3 -o ${OUT}/other2.film)
expect_run(NAME merge-other-scene EXIT 2 MATCH "other2.film: error: is a part of another render: it has \"scene=other-box.pbrt"
           ARGS merge ${OUT}/part1.film ${OUT}/other2.film ${OUT}/part3.film -o ${OUT}/patchwork.exr)
expect_run(NAME merge-twice EXIT 2 MATCH "part1.film: error: is part 1/3 again"
           ARGS merge ${OUT}/part1.film ${OUT}/part1.film -o ${OUT}/merged.exr)
expect_run(NAME part-bad EXIT 2 MATCH "--part: must be K/N with 1 <= K <= N"
           ARGS ${pt_args} --part 3/2 -o ${OUT}/x.film)

message(STATUS "cli end-to-end: all checks passed")
