"""Whether this process has a usable Vulkan device, as a pytest mark for the
tests that need one (lavapipe in CI)."""
import numpy as np
import pytest

import vkfuse


def vulkan_available():
    try:
        vkfuse.fuse([np.zeros((8, 8)), np.ones((8, 8))], method="brovey", backend="vulkan")
        return True
    except vkfuse.Error as e:
        if "no usable Vulkan device" in str(e):
            return False
        raise


needs_vulkan = pytest.mark.skipif(not vulkan_available(), reason="no usable Vulkan device")
