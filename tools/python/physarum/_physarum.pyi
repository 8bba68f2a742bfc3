

def read_mesh(path: str) -> tuple:
    """
    The mesh in `path` (OBJ, PLY, OFF, STL, ...) or a built-in shape ('shape:sphere'), as loaded and repaired by physarum: (V, F), V (n, 3) float64, F (m, 3) int64.
    """

def devices() -> list:
    """
    The OpenCL devices, as `physarum devices` lists them: a list of dicts (index: what device= takes).
    """
