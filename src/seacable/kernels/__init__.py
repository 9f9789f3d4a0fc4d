"""The compiled kernels. Importing any of them first keys numba's on-disk cache of the package
by all its compiled sources (kernels.stamp): every compiled module imports a kernel."""

from seacable.kernels import stamp

stamp.install()
