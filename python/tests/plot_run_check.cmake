# SPDX-License-Identifier: MIT
# ctest python.example_plot_run: runs examples/python/plot_run.py once into OUTPUT and checks
# that it wrote a PNG image (its 8-byte signature) of some size. The script's old output is
# removed first, so a run that writes nothing fails.
#   cmake -DPYTHON=... -DSCRIPT=... -DPROGRAM=... -DTOOLS=... -DOUTPUT=FILE.png -P this
file(REMOVE "${OUTPUT}")
execute_process(
  COMMAND "${PYTHON}" "${SCRIPT}" "${PROGRAM}" --tools "${TOOLS}" --output "${OUTPUT}"
  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "plot_run.py exited with ${rc}:\n${out}${err}")
endif()
if(NOT EXISTS "${OUTPUT}")
  message(FATAL_ERROR "plot_run.py did not write ${OUTPUT}:\n${out}${err}")
endif()
file(SIZE "${OUTPUT}" size)
file(READ "${OUTPUT}" signature LIMIT 8 HEX)
if(NOT signature STREQUAL "89504e470d0a1a0a" OR size LESS 10000)
  message(FATAL_ERROR "${OUTPUT} is not a PNG image of a plot (signature ${signature}, "
                      "${size} bytes)")
endif()
if(NOT out MATCHES "wrote .*plot_run_test.png")
  message(FATAL_ERROR "plot_run.py did not say where it wrote the plot:\n${out}${err}")
endif()
message(STATUS "plot_run.py: ${OUTPUT}, ${size} bytes")
file(REMOVE "${OUTPUT}")
