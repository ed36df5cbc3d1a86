"""Error types of tcasim (the compiled core raises them; docs/python.md)."""


class InputError(ValueError):
    """Bad user input, naming the key path, the value and the rule.

    ``str(e)`` is ``"<key> = <value> <rule>"``, e.g.
    ``"actuators[1].drive.temperature_degC = -400 is below absolute zero"``.
    """

    def __init__(self, key, value, rule):
        super().__init__(f"{key} = {value} {rule}")
        self.key = key
        self.value = value
        self.rule = rule

    def __reduce__(self):  # picklable (Dask ships errors between processes)
        return (type(self), (self.key, self.value, self.rule))


class DomainError(ValueError):
    """A computed state outside the model's domain of validity (e.g. a TCA pitch angle
    leaving (0, 90 deg))."""


class SolverError(RuntimeError):
    """A solve that ran but did not converge. ``.result`` holds the partial result (a
    tcasim.Result for solve, the output document for inverse and grasp), ``.message``
    the solver's reason."""

    def __init__(self, message, result=None):
        super().__init__(message)
        self.message = message
        self.result = result

    def __reduce__(self):
        return (type(self), (self.message, None))
