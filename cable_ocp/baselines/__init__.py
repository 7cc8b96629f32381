"""Other methods for the same scenes, each returning a StaticsSolution (for comparison)."""
