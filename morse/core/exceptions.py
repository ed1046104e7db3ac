"""MORSE's `morse.core.exceptions`: what a MORSE component raises. A service raising one fails with its message
(they are ValueErrors: the answer is the message alone, as MORSE's)."""


class MorseError(Exception):
    def __init__(self, value=""):
        super().__init__(value)
        self.value = value

    def __str__(self):
        return str(self.value)


class MorseServiceError(MorseError, ValueError):
    pass


class MorseRPCInvokationError(MorseServiceError):
    """A service could not be started (wrong arguments, a target out of reach ...)."""


class MorseRPCNbArgsError(MorseRPCInvokationError):
    pass


class MorseRPCTypeError(MorseRPCInvokationError):
    pass


class MorseServiceFailed(MorseServiceError):
    pass


class MorseServicePreempted(MorseServiceError):
    pass


class MorseServiceAlreadyRunningError(MorseServiceError):
    def __init__(self, service=None, value=""):
        super().__init__(value)
        self.service = service


class MorseMultinodeError(MorseError):
    pass


class MorseMiddlewareError(MorseError):
    pass


class MorseEnvironmentError(MorseError):
    pass
