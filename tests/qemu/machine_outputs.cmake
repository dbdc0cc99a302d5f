# Machine outputs of the STM32F4 firmware in QEMU (included by tests/qemu/CMakeLists.txt): an SVG
# drawing with a servo pen and a G-code program with spindle, coolant and digital-output words are
# streamed by `curvestep stream`; machine_outputs_test.py reads TIM4 (servo pen) and TIM3 (spindle
# PWM) through the QEMU monitor while they run and the GPIOB BSRR writes from QEMU's -d unimp log,
# against values computed from the reference manual and the pin table. docs/boards.md, "Machine outputs".
# Skipped (77) while curvestep has no `stream`.
if(TARGET curvestep)
  set(name "qemu: stm32f4 firmware drives the servo pen, spindle PWM, coolant and digital outputs from streamed events")
  add_test(NAME "${name}"
           COMMAND ${Python3_EXECUTABLE} ${qemu_dir}/machine_outputs_test.py stm32f4
                   ${PROJECT_BINARY_DIR}/qemu-stm32f4/bin/curvestep_stm32f4_firmware.elf $<TARGET_FILE:curvestep>
                   ${qemu_dir}/wire_exact_machine.json)
  set_tests_properties("${name}" PROPERTIES LABELS "qemu;integration" TIMEOUT 240 SKIP_RETURN_CODE 77
                       FIXTURES_REQUIRED qemu_stm32f4_images)
  # The same hooks in the F1 firmware's App (Cortex-M3, Q16.16) on netduino2: timers only (no GPIO log there).
  set(name "qemu: Cortex-M3 Q16.16 firmware drives the servo pen and spindle PWM timers from streamed events")
  add_test(NAME "${name}"
           COMMAND ${Python3_EXECUTABLE} ${qemu_dir}/machine_outputs_test.py stm32f2-m3
                   ${PROJECT_BINARY_DIR}/qemu-stm32f2-m3/bin/curvestep_stm32f4_firmware.elf $<TARGET_FILE:curvestep>
                   ${qemu_dir}/wire_exact_machine.json --timers-only)
  set_tests_properties("${name}" PROPERTIES LABELS "qemu;integration" TIMEOUT 240 SKIP_RETURN_CODE 77
                       FIXTURES_REQUIRED qemu_stm32f2-m3_images)
endif()
