// px4 stand-in (tests/target/px4/px4_standin): the file target/px4 looks for in a PX4 tree. Not compiled
// for real (see ../../../compile_probe.sh).
