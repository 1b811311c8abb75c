# cmake -DWITH=<built with exceptions> -DWITHOUT=<built without> -P compare.cmake: both must
# exit 0 and print the same lines (make() results and step hashes, make_cases.cpp; the JSON
# loaders' messages and step hashes, json_cases.cpp).
foreach(which WITH WITHOUT)
  execute_process(COMMAND ${${which}} OUTPUT_VARIABLE out_${which} ERROR_VARIABLE err_${which}
                  RESULT_VARIABLE rc_${which})
  if(NOT rc_${which} EQUAL 0)
    message(FATAL_ERROR "${${which}} failed (${rc_${which}}):\n${err_${which}}")
  endif()
endforeach()
if(NOT out_WITH STREQUAL out_WITHOUT)
  file(WRITE ${WITH}.out "${out_WITH}")
  file(WRITE ${WITHOUT}.out "${out_WITHOUT}")
  message(FATAL_ERROR "the outputs differ: diff ${WITH}.out ${WITHOUT}.out")
endif()
string(REGEX MATCHALL "\n" lines "${out_WITH}")
list(LENGTH lines n)
message(STATUS "${n} lines alike; ${err_WITHOUT}")
