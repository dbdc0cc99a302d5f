(Created by bCNC)
G21
G90
(Block-name: Header)
(Block-expand: 0)
(Block-enable: 1)
M3 S12000
(Block-name: Rectangle)
(Block-expand: 0)
(Block-enable: 1)
G0 Z3
G0 X0 Y0
G1 Z-0.5 F100
G1 X20 F500
G1 Y15
G1 X0
G1 Y0
G0 Z3
(Block-name: Footer)
M5
G0 X0 Y0
