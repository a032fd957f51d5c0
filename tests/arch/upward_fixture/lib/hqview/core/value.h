#pragma once
// Fixture: a core header that is fine.
