// This work is licensed under the POV-Ray v3.7 distribution license.
// To view a copy of this license, visit http://www.povray.org/licences/v3.7/.
//
// The following exception is granted to the above license terms:
// Permission is granted for this file and the output from it to be
// freely redistributed in an unmodified form for the purpose of
// generating and maintaining POV-Ray benchmarks.  Derivative works
// are permitted provided that they have a clearly different filename
// and do not claim to be the standard benchmark file.
//

// Persistence Of Vision Ray Tracer Scene Description File
//
// File:            benchmark.pov
// Benchmark Vers:  2.01 Scene File Version
// Desc:            POV-Ray benchmark scene
// Date:            October/November 2001
//
// Assembled by Christoph Hormann
// Contributions by:
//    - Ingo Janssen
//    - Mick Hazelgrove
//
// ==================================================================
//
//    Standard POV-Ray benchmark version 2.01 Scene File Version
//
// This is the official POV-Ray benchmark scene.  It is designed
// to test a variety of POV-Ray features and should render in a
// reasonable amount of time on current machines.  Note that the
// radiosity feature is still experimental and not very suitable for
// comparing results of different versions, therefore it is turned
// off by default.
//
// Please log all changes made to this file below.
//
// Note that only results generated with the above options and the
// unchanged scene file are allowed to be published as 'official
// POV-Ray benchmark results'.  Feel free to do additional tests, but
// make sure the differences are made clear when publishing them.
//
// When publishing results, be sure to quote the exact version of the
// benchmark scene used (2.01 Scene File Version), and the exact
// version of POV-Ray.
//
// ==================================================================
//
// Change history
// --------------
//
// Nov. 2001   Initial release (version 3.5.0)
// Jan. 2002   using 'max()' instead of '&' in isosurface
// Apr. 2002   changed max_gradient of isosurface (new ver is 1.01)
// Jun. 2002   added photons pass_through to clouds (new ver is 1.02)
// Dec. 2010   made ready for v3.7 release (new ver is 2.00)
// Oct. 2012   allow run without installation (same ver : 2.00)
// Jan. 2013   change version to 2.01 to differentiate from beta.
// Feb  2013   Updated for 3.7
//
// ==================================================================
//
// Suggested command line options if not using an INI file:
//
// -w512 -h512 +a0.3 +v -d -f -x
//
// The following INI options are used when the 'Run Benchmark' command
// is chosen on versions of POV-Ray that support the built-in version.
//
// All_Console=On
// All_File=
// Antialias_Depth=3
// Antialias=On
// Antialias_Gamma=2.5
// Antialias_Threshold=0.3
// Bits_Per_Color=8
// Bounding=On
// Bounding_Method=1
// Bounding_Threshold=3
// Clock=0
// Continue_Trace=Off
// Clockless_