# The unit with its simulation assertions (--assert): the configuration
# contract (rtl/izhikevich_layer.v), whose firing the test checks.
set(eskin_default_args --assert)
