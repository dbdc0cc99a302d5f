# The image each STM32 board ships: the one that meets real time on every example and polyline job
# (docs/boards.md, "Real time"; benchmarks/qemu/results/tick_budget.json). On both boards it is the
# executor (no planner: `curvestep stream` plans on the host, the board replays the pieces). The
# other images are bench and test images, not real-time: bring-up (line monitor), firmware (plans
# on the board; HIL bit-identity tests; its planning takes far longer than a tick) and benchmark.
# Read by curvestep_stm32_image (boards/stm32_common: the install rule and the list the build
# prints) and by the check of the recorded benchmark run (benchmarks/CMakeLists.txt), which fails
# unless every image named here meets the budget on every job there.
set(CURVESTEP_SHIPPED_IMAGES curvestep_stm32f1_executor curvestep_stm32f4_executor)
