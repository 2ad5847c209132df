# adb_set_warnings(target): the project's warning set, applied per target (never directory-wide,
# so that third-party headers included as SYSTEM stay quiet).
function(adb_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wconversion
    -Wno-sign-conversion)
endfunction()
