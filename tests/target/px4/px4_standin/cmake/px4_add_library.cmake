# Stand-in for PX4's px4_add_library(target sources...): a static library of those sources.
function(px4_add_library target)
	add_library(${target} STATIC ${ARGN})
	target_compile_definitions(${target} PRIVATE MODULE_NAME="${target}")
endfunction()
