board/evms_sync.sv
board/evms_crc16_pkg.sv
board/evms_aer_rx.sv
board/evms_uart_rx.sv
board/evms_uart_tx.sv
board/evms_link_rx.sv
board/evms_link_tx.sv
board/evms_board.sv
