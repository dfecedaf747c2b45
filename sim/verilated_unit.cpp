// Anchors the Verilated sources of a core build in a library of its own.
