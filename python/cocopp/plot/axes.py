"""What a figure's axes show: the coordinate along the interface, the component of a vector
variable, and their labels."""
import numpy as np

from cocopp.results import AXES


def along_axis(coordinates, axis=None):
    """The coordinate index along the interface: `axis` ("x", "y", "z") or the longest extent."""
    return AXES[axis] if axis else int(np.argmax(np.ptp(coordinates, axis=0)))


def varying_component(values, component=None):
    """`component`, or the component of (..., c) values that varies most."""
    if component is None:
        component = int(np.argmax(np.ptp(values.reshape(-1, values.shape[-1]), axis=0)))
    return min(component, values.shape[-1] - 1)


def label(variable, components, component, unit):
    name = variable if components == 1 else f"{variable}[{'xyz'[component]}]"
    return f"{name} ({unit})" if unit else name
